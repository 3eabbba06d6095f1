#pragma once
// The light-probe flags (docs/probes.md, "Knobs"), one registration each for every command
// that renders probes (render, dataset generate and slurm, bench probes). Each binds to the
// render::ProbeSettings field it sets and shows that field's value as its default (the
// struct's, probe_settings.h, or a preset's); the flag registry maps the setting names
// ProbeSettings::validate reports ("probe.grid", "probe.spp", "probe.cache.cell_size", ...)
// to these flags.
#include <map>
#include <string>

#include <CLI/CLI.hpp>

#include "phyir/render/probe_settings.h"

namespace phyir::cli {

// Which flags of the group a command takes.
enum ProbeFlags : unsigned {
  kProbeGrid = 1u << 0,        // --probe-grid HxW
  kProbeResolution = 1u << 1,  // --probe-res hxw
  kProbeSampling = 1u << 2,    // --probe-spp, --probe-mode
  kProbeOffset = 1u << 3,      // --probe-offset
  kProbeCache = 1u << 4,       // --probe-cache-cell, --probe-cache-spp, --probe-cache-direct-cells,
                               // --probe-spread-threshold, --probe-share-radius, --probe-share-parallax
  kProbePhotons = 1u << 5,     // --probe-photons
  kProbePunctual = 1u << 6,    // --no-probe-punctual-lights
  kProbeBalance = 1u << 7,     // --probe-balance
  kAllProbeFlags = (1u << 8) - 1,
};

// Registers the flags `which` on `cmd`, writing into `probe` (which must outlive `cmd`).
// `also_named` gives a flag a second name a command kept from before the group
// ({"--probe-grid", "--grid"}).
void add_probe_flags(CLI::App* cmd, render::ProbeSettings& probe, unsigned which = kAllProbeFlags,
                     const std::map<std::string, std::string>& also_named = {});

}  // namespace phyir::cli
