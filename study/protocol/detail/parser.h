// Internal: turns a parsed TOML document into a Protocol plus diagnostics.
// The sections are read in dependency order (factors before the tables keyed
// by their levels, those before the ordering and the questionnaire); a
// section whose inputs had errors skips the cross-checks that would only
// repeat them. Every problem is reported, none aborts the parse.
#pragma once
#include <toml++/toml.h>

#include <string>
#include <vector>

#include "study/protocol/detail/reader.h"
#include "study/protocol/protocol.h"

namespace dtlab::protocol::detail {

struct ParseState {
  ParseState(Diagnostics& diagnostics, Protocol& protocol) : d(diagnostics), p(protocol) {}
  Diagnostics& d;
  Protocol& p;

  bool participants_ok = false;
  Pos participants_pos;

  bool factors_ok = false;             // factors parsed without error
  std::vector<Pos> factor_pos;         // where each factor's name is written
  std::vector<Pos> factor_levels_pos;  // where each factor's levels array is
  int scenario_factor = -1;            // factor with role = "scenario", if any
  int rendering_factor = -1;           // factor with role = "rendering", if any

  bool scenarios_ok = false;   // every scenario and task parsed, levels matched
  bool renderings_ok = false;  // every rendering parsed, levels matched
};

// Reads the whole document (the root table) into s.p. Entry point.
void parse_document(const toml::table& root, ParseState& s);

// [session], [training], [consent], [pages.*], [breaks] (parse_flow.cpp).
void parse_flow(TableReader& root, ParseState& s);

// Sections (parse_design.cpp).
void parse_factors(TableReader& root, ParseState& s);
void build_conditions(ParseState& s);
void parse_order(TableReader& root, ParseState& s);

// Sections (parse_content.cpp).
void parse_scenarios(TableReader& root, ParseState& s);
void parse_renderings(TableReader& root, ParseState& s);
// [questionnaire.*] (parse_questionnaire.cpp); after factors, scenarios and renderings.
void parse_questionnaire(TableReader& root, ParseState& s);

// Sections (parse_people.cpp).
void parse_demographics(TableReader& root, ParseState& s);
// [reference_results] (parse_reference.cpp); after factors, scenarios and the questionnaire.
void parse_reference_results(TableReader& root, ParseState& s);

// Index of `name` in `names`, -1 if absent.
int find_index(const std::vector<std::string>& names, const std::string& name);
// Names of the declared factors, in file order.
std::vector<std::string> factor_names(const Protocol& p);

}  // namespace dtlab::protocol::detail
