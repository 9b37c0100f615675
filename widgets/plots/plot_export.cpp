#include "widgets/plots/plot_export.h"

#include <qcustomplot.h>

#include <QFile>
#include <QFileInfo>
#include <QSvgGenerator>

#include "core/io/atomic_file.h"
#include "core/io/csv.h"
#include "widgets/plots/plot_legend.h"
#include "widgets/plots/plot_theme.h"

namespace terra::ui {
namespace {

bool writeSvg(QCustomPlot& plot, const QString& path, const ExportOptions& o) {
    QSvgGenerator generator;
    generator.setFileName(path);
    generator.setSize(QSize(o.width, o.height));
    generator.setViewBox(QRect(0, 0, o.width, o.height));
    generator.setResolution(o.dpi);
    generator.setTitle("TerraStudio plot");
    QCPPainter painter;
    if (!painter.begin(&generator)) return false;
    plot.toPainter(&painter, o.width, o.height);
    return painter.end();
}

}  // namespace

bool exportPlot(QCustomPlot& plot, const QString& path, const ExportOptions& options,
                QString* error) {
    if (options.width < 16 || options.height < 16 || options.width > 20000 ||
        options.height > 20000 || options.dpi < 10 || options.dpi > 2400) {
        if (error)
            *error = QString("export size %1 × %2 at %3 dpi is outside 16–20000 px, 10–2400 dpi")
                         .arg(options.width)
                         .arg(options.height)
                         .arg(options.dpi);
        return false;
    }
    const QString suffix = QFileInfo(path).suffix().toLower();
    const QString temporary = path + ".part." + suffix;
    bool ok = false;
    // Light colours for the file unless asked otherwise; the screen gets its palette back after.
    // Only plots whose frame follows the palette (plot_theme.h) are re-coloured: others keep the
    // colours their drawing code chose (e.g. axes tinted like their curves).
    struct ScreenColours {
        QCustomPlot& plot;
        bool relight;
        ~ScreenColours() {
            if (!relight) return;
            applyPlotTheme(plot, PlotTheme::fromPalette(plot.palette()));
            plot.replot(QCustomPlot::rpQueuedReplot);
        }
    } screen{plot, !options.screen_colours && followsPalette(plot)};
    if (screen.relight) applyPlotTheme(plot, PlotTheme::light());
    // The legend where the screen has it (dragged, hidden or under the axes), its columns fitted
    // to the export's width as they are to the screen's; the screen's layout comes back after.
    struct ScreenLegend {
        QCustomPlot& plot;
        ~ScreenLegend() {
            layOutLegend(plot);
            plot.replot(QCustomPlot::rpQueuedReplot);
        }
    } legend{plot};
    layOutLegend(plot, options.width);
    if (suffix == "png") {
        ok = plot.savePng(temporary, options.width, options.height, options.scale, -1, options.dpi);
    } else if (suffix == "svg") {
        ok = writeSvg(plot, temporary, options);
    } else if (suffix == "pdf") {
        ok = plot.savePdf(temporary, options.width, options.height, QCP::epNoCosmetic,
                          "TerraStudio", "plot");
    } else {
        if (error)
            *error = "unknown image format \"" + suffix + "\" of " + path + " (png, svg, pdf)";
        return false;
    }
    if (!ok || !QFileInfo(temporary).exists()) {
        if (error) *error = "cannot write " + path;
        QFile::remove(temporary);
        return false;
    }
    QFile::remove(path);
    if (!QFile::rename(temporary, path)) {
        if (error) *error = "cannot rename " + temporary + " to " + path;
        QFile::remove(temporary);
        return false;
    }
    return true;
}

bool exportTable(const Table& table, const QString& path, QString* error) {
    if (const auto failure = io::writeFileAtomically(path.toStdString(), io::toCsv(table))) {
        if (error) *error = QString::fromStdString(*failure);
        return false;
    }
    return true;
}

}  // namespace terra::ui
