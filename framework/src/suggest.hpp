// "Did you mean ...?" for misspelt keys and model names.
#pragma once

#include <string>
#include <vector>

namespace topomill {

// The candidate closest to `word` by edit distance, if close enough to be a likely typo; else "".
std::string closest_name(const std::string& word, const std::vector<std::string>& candidates);

// "<message>; did you mean 'x'? <list_title>: a, b, c" (the question only when one is close).
std::string with_candidates(const std::string& message, const std::string& word,
                            const std::vector<std::string>& candidates,
                            const std::string& list_title);

}  // namespace topomill
