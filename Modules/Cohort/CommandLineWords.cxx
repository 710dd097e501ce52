#include <vimlop/Cohort/CommandLineWords.h>

#include <vimlop/Core/Error.h>

namespace vimlop
{

std::vector<std::string> splitCommandLine(const std::string& text)
{
  std::vector<std::string> words;
  std::string word;
  bool inWord = false;
  char quote = 0;
  for (size_t i = 0; i < text.size(); ++i)
  {
    const char c = text[i];
    if (quote)
    {
      if (c == quote)
      {
        quote = 0;
      }
      else if (c == '\\' && quote == '"' && i + 1 < text.size())
      {
        word += text[++i];
      }
      else
      {
        word += c;
      }
    }
    else if (c == '\'' || c == '"')
    {
      quote = c;
      inWord = true;
    }
    else if (c == '\\' && i + 1 < text.size())
    {
      word += text[++i];
      inWord = true;
    }
    else if (c == ' ' || c == '\t' || c == '\n' || c == '\r')
    {
      if (inWord)
      {
        words.push_back(word);
        word.clear();
        inWord = false;
      }
    }
    else
    {
      word += c;
      inWord = true;
    }
  }
  if (quote)
  {
    throw Error(std::string("an unterminated ") + (quote == '"' ? "double" : "single") +
      " quote in '" + text + "'");
  }
  if (inWord)
  {
    words.push_back(word);
  }
  return words;
}

std::string joinCommandLine(const std::vector<std::string>& words)
{
  std::string text;
  for (const std::string& word : words)
  {
    const bool plain = !word.empty() &&
      word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"
                             "-_./:=,+@%") == std::string::npos;
    std::string quoted = "'";
    for (char c : word)
    {
      quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    }
    text += (text.empty() ? "" : " ") + (plain ? word : quoted + "'");
  }
  return text;
}

} // namespace vimlop
