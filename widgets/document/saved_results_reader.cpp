#include "widgets/document/saved_results_reader.h"

#include <QFutureWatcher>
#include <QtConcurrent/QtConcurrentRun>
#include <optional>

namespace terra::ui {

void readSavedResults(const QString& path, QObject* context,
                      std::function<void(const Result<project::SavedResults>&)> done) {
    // QFuture needs a default-constructible value: Result has none, its optional has.
    using Read = std::optional<Result<project::SavedResults>>;
    auto* watcher = new QFutureWatcher<Read>(context);
    QObject::connect(watcher, &QFutureWatcher<Read>::finished, context, [watcher, done] {
        watcher->deleteLater();
        done(*watcher->result());
    });
    watcher->setFuture(QtConcurrent::run(
        [file = path.toStdString()]() -> Read { return project::loadResults(file); }));
}

}  // namespace terra::ui
