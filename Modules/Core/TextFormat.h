#ifndef vimlop_TextFormat_h
#define vimlop_TextFormat_h

#include <string>

namespace vimlop
{

/**
 * @brief printf-style formatting into a string, for the one-line summaries
 * the typed reports give every face (the program, Python) to print alike.
 */
#if defined(__GNUC__)
__attribute__((format(printf, 1, 2)))
#endif
std::string
formatText(const char* format, ...);

/// @brief `text` with &, <, > and " as HTML entities, for the report pages.
std::string escapeHtml(const std::string& text);

/// @brief `text` without the spaces, tabs and line ends at its start and end.
std::string trimmed(const std::string& text);

/// @brief `text` with its ASCII letters in lower case, for names compared without case.
std::string lowerCase(std::string text);

/// @brief The extension of the file name `path` in lower case, with its dot
/// (".mha"), or "" when it has none: how the readers tell formats apart.
std::string lowerCaseExtension(const std::string& path);

} // namespace vimlop

#endif
