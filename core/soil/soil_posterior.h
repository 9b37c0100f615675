#pragma once
/// @file soil_posterior.h
/// Soil parameters known as a multivariate normal: an identification's posterior (what
/// `identify --save-soil` writes beside the identified soil, analysis/soil_posterior.h reads and
/// `traction --posterior` samples from) or the streaming identifier's estimate with its covariance
/// (the optimal slip controller's robust set-point, docs/traction.md §8). Plain data, in the soil
/// file's keys and units.

#include <string>
#include <vector>

namespace terra::soil {

/// {"parameters": [soil file keys], "mean": [...], "covariance": [[...]]}, in the keys' units.
struct SoilPosterior {
    std::vector<std::string> parameters;
    std::vector<double> mean;
    std::vector<std::vector<double>> covariance;
    /// What reading it noted (an old parameter key read as its new one, issue 26); not data.
    std::vector<std::string> notes;
};

}  // namespace terra::soil
