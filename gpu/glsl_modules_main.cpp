// prism-glsl-modules FILE: prints the modules FILE's `// prism:require`
// lines name, one a line, as the kernel generator reads them
// (prism/sdk/shared_source.hpp), so that scripts/check_plugin_glsl.sh
// assembles a plugin's shader with the generator's one parser. Exit status
// 2 with a message naming the file for an unreadable file or a malformed
// directive.
#include <fstream>
#include <iostream>
#include <sstream>

#include "prism/sdk/shared_source.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: prism-glsl-modules FILE\n";
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  if (!in) {
    std::cerr << "prism-glsl-modules: cannot read " << argv[1] << '\n';
    return 2;
  }
  std::ostringstream text;
  text << in.rdbuf();
  const prism::sdk::RequiredModules required = prism::sdk::required_modules(text.str());
  if (!required.problem.empty()) {
    std::cerr << "prism-glsl-modules: " << argv[1] << ": " << required.problem << '\n';
    return 2;
  }
  for (const std::string& m : required.modules) std::cout << m << '\n';
  return 0;
}
