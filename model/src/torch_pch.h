#pragma once
// Precompiled header of phyir_model and model_test: torch/torch.h takes ~30 s to parse.
#include <torch/torch.h>

#include <cmath>
#include <string>
#include <vector>
