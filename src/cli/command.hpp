// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// A subcommand of the breastsim CLI: its CLI11 parser and the action run
// after a successful parse (returns the exit code). Each subcommand lives in
// its own file and is listed once in main.cpp.
#include <CLI/CLI.hpp>
#include <functional>

namespace breastsim::cli
{
struct Command
{
  CLI::App* app;
  std::function<int()> run;
};

Command add_simulate_command(CLI::App& root);
Command add_keys_command(CLI::App& root);
Command add_calibrate_command(CLI::App& root); // and `measure` (calibrate_command.cpp)
Command add_measure_command(CLI::App& root);
Command add_view_command(CLI::App& root);
Command add_surgery_command(CLI::App& root);
Command add_sweep_command(CLI::App& root);
Command add_converge_command(CLI::App& root); // converge_command.cpp
Command add_record_command(CLI::App& root);   // record_command.cpp
Command add_diagnose_command(CLI::App& root); // diagnose_command.cpp
Command add_serve_command(CLI::App& root);    // serve_command.cpp
Command add_neutral_state_command(CLI::App& root); // neutral_state_command.cpp
Command add_scan_model_command(CLI::App& root);    // scan_model_command.cpp
Command add_synthetic_patient_command(CLI::App& root); // synthetic_patient_command.cpp
Command add_scan_calibrate_command(CLI::App& root);   // scan_calibrate_command.cpp
Command add_patient_command(CLI::App& root);          // patient_command.cpp
Command add_plan_command(CLI::App& root);             // plan_command.cpp
} // namespace breastsim::cli
