#include <vector>

#include "common/arguments.hpp"
#include "fuzz_input.hpp"

// A command line: the input's NUL-separated words after a program name, parsed with the kind of
// options the tools declare, then every value read as text, integer and number.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> words{"lidar_sgm_densify"};
  std::string word;
  for (std::size_t i = 0; i < size; ++i) {
    if (data[i] == 0) {
      words.push_back(word);
      word.clear();
    } else {
      word.push_back(static_cast<char>(data[i]));
    }
  }
  words.push_back(word);
  std::vector<const char*> argv;
  for (const std::string& w : words) argv.push_back(w.c_str());
  lidar_sgm::fuzz::expectCleanRefusal([&] {
    const lidar_sgm::apps::Arguments arguments(static_cast<int>(argv.size()), argv.data(),
                                               {"alpha", "disparities", "format", "image_size", "o"}, {"v", "q"});
    for (const auto& option : arguments.values()) {
      arguments.text(option.first, "");
      lidar_sgm::fuzz::expectCleanRefusal([&] { arguments.integer(option.first, 0); });
      arguments.number(option.first, 0.0);
    }
  });
  return 0;
}
