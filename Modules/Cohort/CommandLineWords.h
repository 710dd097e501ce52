#ifndef vimlop_CommandLineWords_h
#define vimlop_CommandLineWords_h

#include <string>
#include <vector>

/**
 * @file CommandLineWords.h
 * @brief Command lines as words and back, the way a POSIX shell reads them:
 * a manifest's `options` column, and the command lines a cohort and a
 * result folder record.
 */

namespace vimlop
{

/**
 * @brief Splits a command-line text into words as a shell would for plain
 * words: blanks separate them, single or double quotes keep blanks inside
 * one, a backslash escapes the next character (the `options` column).
 * @throws vimlop::Error on an unterminated quote.
 */
std::vector<std::string> splitCommandLine(const std::string& text);

/**
 * @brief Words joined into one command line a POSIX shell (and
 * splitCommandLine()) reads back as the same words: a word with anything
 * but letters, digits and -_./:=,+@% is single-quoted.
 */
std::string joinCommandLine(const std::vector<std::string>& words);

} // namespace vimlop

#endif
