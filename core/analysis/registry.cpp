#include "core/analysis/registry.h"

#include "core/analysis/compaction.h"
#include "core/analysis/forces.h"
#include "core/analysis/global_sensitivity.h"
#include "core/analysis/identification.h"
#include "core/analysis/rover.h"
#include "core/analysis/sensitivity.h"
#include "core/analysis/sinkage_study.h"
#include "core/analysis/soil_curves.h"
#include "core/analysis/streaming_identification.h"
#include "core/analysis/stresses.h"
#include "core/analysis/traction.h"
#include "core/analysis/validation.h"

namespace terra::analysis {

const std::vector<AnalysisType>& analysisTypes() {
    // One line per analysis: a new one is added here (docs/architecture.md, "Adding an analysis").
    static const std::vector<AnalysisType> types{
        forcesType(),          soilCurvesType(),  stressesType(),
        sinkageType(),         sensitivityType(), identificationType(),
        streamingType(),       roverType(),       globalSensitivityType(),
        uncertaintyBandType(), validationType(),  compactionType(),
        tractionType(),
    };
    return types;
}

const AnalysisType* findAnalysisType(std::string_view name) {
    for (const AnalysisType& type : analysisTypes()) {
        if (type.name == name) return &type;
    }
    return nullptr;
}

std::vector<std::string> analysisTypeNames() {
    std::vector<std::string> names;
    for (const AnalysisType& type : analysisTypes()) names.push_back(type.name);
    return names;
}

}  // namespace terra::analysis
