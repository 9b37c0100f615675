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
    if (mark.isEmpty()) return title;
    // A title of two lines (soil, wheel and load; then the case) takes the mark on a third: after
    // the second it made the line too long for a ~400 px plot.
    return title.contains('\n') ? title + "\n" + mark : title + " — " + mark;
}

QString progressFormat(Completion completion) {
    const QString w = word(completion);
    return w.isEmpty() ? QString("%p %") : QString("%p % (%1)").arg(w);
}

}  // namespace terra::ui
