// mpsolid: the command line (src/app/command_line.hpp), then the launch
// (src/app/launch.hpp).
#include <variant>

#include "src/app/command_line.hpp"
#include "src/app/launch.hpp"

int main(int argc, char** argv) {
  auto parsed = mpsolid::parse_command_line(argc, argv);
  if (const int* exit_code = std::get_if<int>(&parsed)) return *exit_code;
  return mpsolid::launch(std::get<mpsolid::CommandLine>(parsed), &argc, &argv);
}
