#pragma once
// The little UTF-8 handling speech text needs: walking code points (IPA
// symbols, accented words) and folding Latin letters to their base letter.
#include <cstddef>
#include <string>
#include <string_view>

namespace facial {

// The code point starting at text[pos]; advances pos past it. A broken
// sequence reads as U+FFFD and advances one byte (never loops, never throws).
char32_t nextCodepoint(std::string_view text, size_t& pos);
void appendUtf8(std::string& out, char32_t codepoint);

// The lower-case ASCII letter a Latin letter is written on: 'e' for "é", "ê",
// "ế", "E"; 'd' for "đ"; 'a' for "ă"; 0 for anything else. Covers Latin-1,
// the Latin Extended-A/B letters of French, Vietnamese and pinyin and the precomposed
// Vietnamese vowels (U+1EA0..U+1EF9).
char latinBaseLetter(char32_t codepoint);

// `text` in double quotes for a one-line message: quotes, backslashes and
// control characters (a newline in a phoneme) escaped, as JSON writes them.
std::string quotedForMessage(std::string_view text);

}  // namespace facial
