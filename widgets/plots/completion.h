#pragma once
/// @file completion.h
/// How complete a shown result is, in the same words wherever it shows: a panel's progress bar,
/// status line and plot titles, the studio's status bar and the exported figures (the CLI's too).
/// A cancelled, diverged or failed run keeps what it computed and says so (STYLE.md, "Errors").

#include <QString>

namespace terra::ui {

enum class Completion {
    kComplete,   ///< the whole computation ran
    kCancelled,  ///< stopped by the user: what was computed before the cancel
    kDiverged,   ///< a simulation that diverged: the steps before
    kFailed,     ///< stopped by an error part way: the parts before
};

/// "" when complete, else "CANCELLED (partial)", "DIVERGED (partial)" or "FAILED (partial)".
QString completionMark(Completion completion);

/// `title` followed by " — " and completionMark() when the result is partial (a title of two or
/// more lines: the mark on a line of its own).
QString markedTitle(const QString& title, Completion completion);

/// A progress bar's format: "%p %" when complete, else "%p % (cancelled)", "%p % (diverged)" or
/// "%p % (failed)": a partial run's bar stays where it stopped and says why.
QString progressFormat(Completion completion);

}  // namespace terra::ui
