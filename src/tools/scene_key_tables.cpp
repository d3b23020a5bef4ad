// Prints the key tables of docs/user/configuration.md from the scene key table
// (hexdyn/config/scene_key_table.hpp), each between the marker lines of its region;
// docs/gen_config_tables.py puts them in the page:
//     hexdyn_scene_key_tables      (the regions on stdout; exit 1 with one line on error)
#include <exception>
#include <iostream>

#include "hexdyn/config/scene_key_docs.hpp"

int main() {
  try {
    std::cout << hexdyn::scene_key_regions();
    return std::cout ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "hexdyn_scene_key_tables: " << e.what() << "\n";
    return 1;
  }
}
