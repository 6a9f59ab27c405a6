// mutation.hpp: the mutation campaigns over rtl/, the public header of hc_mutation.
//   vhdl_mutants.hpp  the generator: every single-point mutant of a VHDL design file
//   campaign.hpp      the generated campaign: each generated mutant stillborn, killed by
//                     co-simulation or proven equivalent by yosys (alone or under proven
//                     assumptions), its verdict a Fate; the report and the verdict list (CSV)
//   smoke.hpp         the hand-written smoke list (mutations.json): caught and localised
//   mutated_run.hpp   the run both campaigns make of a mutant: a scratch copy of rtl/ with
//                     one edit, analysed with GHDL mcode and co-simulated
#pragma once

#include "mutation/campaign.hpp"
#include "mutation/mutated_run.hpp"
#include "mutation/smoke.hpp"
#include "mutation/vhdl_mutants.hpp"
