#pragma once
/// @file saved_results_reader.h
/// Reads a project's results file (core/project/results.h) on a worker thread, so that opening a
/// project with a long rover run or a large streaming playback saved beside it never holds the
/// GUI thread, and hands the result to the GUI thread.

#include <QObject>
#include <QString>
#include <functional>

#include "core/project/results.h"

namespace terra::ui {

/// Reads `path` off the GUI thread; calls `done` with what was read (or why not) on `context`'s
/// thread, unless `context` was destroyed first.
void readSavedResults(const QString& path, QObject* context,
                      std::function<void(const Result<project::SavedResults>&)> done);

}  // namespace terra::ui
