// The evaluation report of the command line: a table on stdout and the same as JSON.
#pragma once

#include <string>
#include <vector>

#include "engine/document/scene.h"
#include "engine/eval/evaluator.h"

namespace strata {

struct ReportContext {
  std::string input;  // scene file or the operands of `boolean`
  std::string unit;   // length unit of the scene
  int treeDepth = 0;
  std::vector<std::string> warnings;
  std::string output;  // file written with -o, if any
  uint64_t outputPoints = 0;
};

std::string formatReportText(const EvalResult& result, const ReportContext& context,
                             bool listNodes);
std::string formatReportJson(const EvalResult& result, const ReportContext& context);

}  // namespace strata
