// kerf: soft-tissue cutting simulation, FEM against enriched meshless methods.
#include "app/cli.h"

int main(int argc, char** argv) {
  return kerf::run_command_line(std::vector<std::string>(argv + 1, argv + argc));
}
