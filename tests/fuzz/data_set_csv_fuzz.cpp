// Fuzz harness: the identification data set (identification::parseDataSet, the reader of
// `identify --data` and of the studio's identification panel), with both bad-row policies and both
// column needs.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "core/identification/data_set.h"
#include "tests/fuzz/fuzz_support.h"

TERRA_FUZZ_HARNESS(data_set_csv) {
    using namespace terra::identification;
    const std::string text = terra::fuzz::textOf(data, size);
    for (BadRows policy : {BadRows::kStop, BadRows::kSkip}) {
        for (ColumnNeeds needs : {ColumnNeeds::kDecoupled, ColumnNeeds::kFullModel}) {
            const terra::Result<DataSetRead> read = parseDataSet(text, "fuzz.csv", policy, needs);
            terra::fuzz::checkResult(read);
            if (!read) continue;
            // What is read is in range: a finite slip in [-1, 1], a finite entry angle.
            for (const Sample& s : read->data.samples) {
                if (!(std::abs(s.slip) <= 1.0)) terra::fuzz::fail("slip outside [-1, 1] read");
                if (!std::isfinite(s.entry_angle_rad) || !std::isfinite(s.fx_n) ||
                    !std::isfinite(s.fz_n) || !std::isfinite(s.my_nm))
                    terra::fuzz::fail("a non-finite value read");
            }
        }
    }
    return 0;
}
