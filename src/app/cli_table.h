// A command's options as a table: each row its names, its help text (docs/cli.md is the long
// form), where its value goes with its check, and the options it excludes. A table reads in
// the order of the command's --help, and adding an option is adding a row.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace mirage {

// Adds one option to a command: (command, names, help) → the option, for the row's excludes.
using AddOption = std::function<CLI::Option*(CLI::App& command, const std::string& names,
                                             const std::string& help)>;

struct CliOption {
    std::string names;  // "-o,--output"; a positional argument's name has no dash
    std::string help;
    AddOption add;
    std::vector<std::string> excludes = {};  // options of earlier rows
};

// A value into `target`.
template <class T>
AddOption value(T* target) {
    return [target](CLI::App& c, const std::string& names, const std::string& help) {
        return c.add_option(names, *target, help);
    };
}

// A value into `target`, refused on the command line unless `check` accepts it.
template <class T>
AddOption value(T* target, const CLI::Validator& check) {
    return [target, check](CLI::App& c, const std::string& names, const std::string& help) {
        return c.add_option(names, *target, help)->check(check);
    };
}

// A flag: `target` is true when given.
inline AddOption flag(bool* target) {
    return [target](CLI::App& c, const std::string& names, const std::string& help) {
        return c.add_flag(names, *target, help);
    };
}

// Every value after the option (--set a=1 b=2).
inline AddOption allValues(std::vector<std::string>* target) {
    return [target](CLI::App& c, const std::string& names, const std::string& help) {
        return c.add_option(names, *target, help)->take_all();
    };
}

// The same option, required.
inline AddOption required(AddOption add) {
    return [add](CLI::App& c, const std::string& names, const std::string& help) {
        return add(c, names, help)->required();
    };
}

// The rows of `table` named in `help`, in its order, each with the help text given there (a
// command that takes some of another's options, bound and checked alike).
inline std::vector<CliOption> selectOptions(
    const std::vector<CliOption>& table,
    const std::vector<std::pair<std::string, std::string>>& help) {
    std::vector<CliOption> rows;
    for (const auto& [names, text] : help)
        for (const CliOption& row : table)
            if (row.names == names) rows.push_back({row.names, text, row.add, row.excludes});
    return rows;
}

// Adds the rows to `command` in order.
inline void addOptions(CLI::App& command, const std::vector<CliOption>& table) {
    for (const CliOption& row : table) {
        CLI::Option* option = row.add(command, row.names, row.help);
        for (const std::string& other : row.excludes) option->excludes(other);
    }
}

}  // namespace mirage
