#include "widgets/plots/completion.h"

namespace terra::ui {
namespace {

/// The lower-case word of a partial result ("cancelled"); empty when complete.
QString word(Completion completion) {
    switch (completion) {
        case Completion::kComplete:
            return {};
        case Completion::kCancelled:
            return "cancelled";
        case Completion::kDiverged:
            return "diverged";
        case Completion::kFailed:
            break;
    }
    return "failed";
}

}  // namespace

QString completionMark(Completion completion) {
    const QString w = word(completion);
    return w.isEmpty() ? QString() : w.toUpper() + " (partial)";
}

QString markedTitle(const QString& title, Completion completion) {
    const QString mark = completionMark(completion);
    return mark.isEmpty() ? title : title + " — " + mark;
}

QString progressFormat(Completion completion) {
    const QString w = word(completion);
    return w.isEmpty() ? QString("%p %") : QString("%p % (%1)").arg(w);
}

}  // namespace terra::ui
