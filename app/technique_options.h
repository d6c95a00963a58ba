// The command-line options the technique registry declares (technique::KeySpec
// with a `cli` name): one option per key, read by the key's own group exactly
// as the protocol's [rendering.*] table is, so that an option and its protocol
// key take the same values and give the same frame settings. `dtlab render`
// adds them; a new method's keys become options without touching the command.
// Never: names a method or a key itself.
#pragma once
#include <deque>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "study/technique/technique.h"

namespace dtlab::app {

class TechniqueOptions {
 public:
  // Adds an option to `cmd` for every registry key with a command-line name.
  void add_to(CLI::App& cmd);
  // The names of the options given, comma-separated ("" if none).
  std::string given() const;
  // "--x, --y apply to --method vdt only" for options whose group `method` does not read; "" if none.
  std::string misplaced(const technique::Technique& method) const;
  // Sets the settings of every group `method` reads that has options, from the options given and
  // the protocol's defaults; a value the group refuses fails with exit 2 naming the option.
  void apply(const technique::Technique& method, int width, int height, technique::MethodSettings& out) const;

 private:
  struct Entry {
    const technique::KeyGroup* group;
    const technique::KeySpec* key;
    CLI::Option* option = nullptr;
    std::string value;
  };
  std::deque<Entry> entries_;  // stable addresses: CLI11 writes into `value`
  bool has_options(const technique::KeyGroup& g) const;
};

}  // namespace dtlab::app
