#include "core/common/quoted.h"

namespace terra {

std::string quoteText(std::string_view text, char mark, std::size_t max_chars) {
    if (text.size() <= max_chars) return mark + std::string(text) + mark;
    std::size_t cut = max_chars;
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
    return mark + std::string(text.substr(0, cut)) + "…" + mark + " (" +
           std::to_string(text.size()) + " characters)";
}

std::string pathLabel(std::string_view path, std::size_t max_chars) {
    return path.size() <= max_chars ? std::string(path) : quoteText(path, '\'', max_chars);
}

}  // namespace terra
