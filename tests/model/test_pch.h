#pragma once
// Precompiled header of model_test (torch/torch.h alone takes ~30 s to parse).
#include <gtest/gtest.h>
#include <torch/torch.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>
