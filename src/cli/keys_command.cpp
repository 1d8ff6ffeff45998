// SPDX-License-Identifier: LGPL-3.0-or-later
// `breastsim keys`: every case-file key with its type, unit, default, allowed
// range and meaning, as a Markdown table (the schema and the UFL terms' parameters).
#include "command.hpp"
#include "log.hpp"
#include "schema.hpp"
#include <iostream>

namespace breastsim::cli
{
Command add_keys_command(CLI::App& root)
{
  auto* app = root.add_subcommand("keys", "print every case-file key (Markdown table)");
  return {app, []()
          {
            if (log::is_root())
              std::cout << schema_markdown();
            return 0;
          }};
}
} // namespace breastsim::cli
