#pragma once
/// @file soil_posterior.h
/// Soil parameters known as a multivariate normal, an identification's posterior: what
/// `identify --save-soil` writes beside the identified soil ("posterior" in the soil file) and
/// what `traction --posterior`, `bands --posterior` and `gsa --posterior` sample from, in the soil
/// file's keys and units (docs/identification.md, "The posterior carried on").

#include <filesystem>
#include <string>
#include <vector>

#include "core/common/issue.h"
#include "core/io/json_reader.h"
#include "core/soil/soil_posterior.h"

namespace terra::analysis {

/// {"parameters": [soil file keys], "mean": [...], "covariance": [[...]]}, in the keys' units
/// (core/soil/soil_posterior.h: the streaming controller builds one too).
using SoilPosterior = soil::SoilPosterior;

/// The soil file key of a posterior parameter: the identification's names (`identify --json`'s
/// and `--save-soil`'s "Ks_kPa", "n0") are the soil's "kphi" (K_s, with k_c = 0 in the saved
/// soil, in the same kN/m^(n+2)) and "n"; every other name is already a soil key.
std::string soilKeyOf(const std::string& name);

/// The posterior of an object with SoilPosterior's keys, problems named (their shape and
/// definiteness are checked by the analyses that use it). Parameters named as the identification
/// names them are translated to soil keys (soilKeyOf).
void readPosterior(io::ObjectReader& r, SoilPosterior& out);

/// The posterior of a file: a soil file holding "posterior" (`identify --save-soil`), or an
/// object of SoilPosterior's keys alone. Issues name the file and the key.
Result<SoilPosterior> readPosteriorFile(const std::filesystem::path& path);

/// Whether a JSON file is a soil file (it has the soil's required key "phi_deg"): a
/// `--posterior` soil file is then also the soil of a command that is given no --soil.
bool isSoilFile(const std::filesystem::path& path);

}  // namespace terra::analysis
