#include "core/io/atomic_file.h"

#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <system_error>

namespace terra::io {

std::optional<std::string> writeFileAtomically(const std::filesystem::path& path,
                                               std::string_view content) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path directory = path.has_parent_path() ? path.parent_path() : fs::path(".");
    if (!fs::is_directory(directory, ec)) {
        return "cannot write " + path.string() + ": directory " + directory.string() +
               " does not exist";
    }
    std::random_device random;
    const fs::path temporary =
        directory / ("." + path.filename().string() + ".tmp" + std::to_string(random()));
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out) return "cannot create " + temporary.string();
        out.write(content.data(), static_cast<std::streamsize>(content.size()));
        out.flush();
        if (!out) {
            out.close();
            fs::remove(temporary, ec);
            return "cannot write " + temporary.string() + " (disk full?)";
        }
    }
    fs::rename(temporary, path, ec);
    if (ec) {
        std::error_code ignored;
        fs::remove(temporary, ignored);
        return "cannot replace " + path.string() + ": " + ec.message();
    }
    return std::nullopt;
}

std::optional<std::string> readFile(const std::filesystem::path& path, std::string& content) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return "cannot open " + path.string();
    std::ostringstream buffer;
    buffer << in.rdbuf();
    content = buffer.str();
    return std::nullopt;
}

}  // namespace terra::io
