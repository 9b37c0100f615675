#include "core/common/quoted.h"

namespace terra {

namespace {

// Control characters as escapes ("\n", "\x1b"): a name with a line break or a terminal escape
// sequence in it must show as what it is, not break or repaint the message.
std::string visible(std::string_view text) {
    std::string out;
    for (const char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (u >= 0x20 && u != 0x7f) {
            out += c;
        } else if (c == '\n') {
            out += "\\n";
        } else if (c == '\r') {
            out += "\\r";
        } else if (c == '\t') {
            out += "\\t";
        } else {
            static const char* const kHex = "0123456789abcdef";
            out += {'\\', 'x', kHex[u >> 4], kHex[u & 0xf]};
        }
    }
    return out;
}

}  // namespace

std::string quoteText(std::string_view text, char mark, std::size_t max_chars) {
    if (text.size() <= max_chars) return mark + visible(text) + mark;
    std::size_t cut = max_chars;
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
    return mark + visible(text.substr(0, cut)) + "…" + mark + " (" + std::to_string(text.size()) +
           " characters)";
}

std::string pathTail(std::string_view path, std::size_t max_chars) {
    if (path.size() <= max_chars) return visible(path);
    std::size_t start = path.size() - (max_chars > 0 ? max_chars - 1 : 0);
    while (start < path.size() && (static_cast<unsigned char>(path[start]) & 0xC0) == 0x80) ++start;
    return "…" + visible(path.substr(start));
}

std::string pathLabel(std::string_view path, std::size_t max_chars) {
    return path.size() <= max_chars ? std::string(path) : quoteText(path, '\'', max_chars);
}

}  // namespace terra
