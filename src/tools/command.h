// One subcommand of `mirage` (render, info, slab, ...): registered on the command line by its
// add...Command function, which binds the options to a struct that `run` then executes.
#pragma once

#include <functional>

namespace CLI {
class App;
}

namespace mirage {

struct Command {
    CLI::App* subcommand = nullptr;  // given on the command line when *subcommand is true
    std::function<int()> run;        // the exit code
};

}  // namespace mirage
