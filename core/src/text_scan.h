#pragma once
/// @file text_scan.h (internal)
/// What svo's own mesh readers share: whitespace tokens over a byte buffer with
/// line numbers, exact number parsing, and quoting of file bytes for messages.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace svo::detail {

inline bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

/// Whitespace-separated tokens across lines; line() is the line of the last
/// token, for messages. Works on the bytes in place: a 68 MB file is read
/// without a string per token.
class TextScanner {
public:
    explicit TextScanner(std::string_view text, size_t firstLine = 1)
        : p_(text.data()), end_(p_ + text.size()), line_(firstLine)
    {
    }

    /// The next token; empty at the end of the text.
    std::string_view next()
    {
        while (p_ < end_ && isSpace(*p_)) line_ += *p_++ == '\n';
        const char* start = p_;
        while (p_ < end_ && !isSpace(*p_)) ++p_;
        return {start, size_t(p_ - start)};
    }
    /// Skips to the start of the next line (for free text such as a solid's name).
    void skipLine()
    {
        while (p_ < end_ && *p_ != '\n') ++p_;
    }
    size_t line() const { return line_; }
    size_t remaining() const { return size_t(end_ - p_); }

private:
    const char* p_;
    const char* end_;
    size_t line_;
};

/// The whole token as a double, correctly rounded (fast_float); a leading '+'
/// is accepted. False for anything malformed. NaN/Inf ("nan", "inf", or too
/// large a number) parse and are left for the caller to refuse by name.
bool parseDouble(std::string_view token, double& out);
/// The whole token as a decimal integer; false if malformed or out of range.
bool parseInt(std::string_view token, int64_t& out);

/// The token for a message, in single quotes: bytes outside printable ASCII as
/// \xNN, long tokens cut, so that no file byte reaches the terminal raw.
std::string quoted(std::string_view token);
/// Text with bytes outside printable ASCII (and backslashes) as \xNN.
std::string escaped(std::string_view text);

/// ASCII case-insensitive equality (STL keywords come in either case).
bool equalsNoCase(std::string_view a, std::string_view b);

} // namespace svo::detail
