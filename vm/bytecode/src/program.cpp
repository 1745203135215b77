#include "meldvm/program.hpp"

namespace meldvm {

std::vector<const CodeBlock*> nativeCodeBlocks(const Program& program) {
  std::vector<const CodeBlock*> blocks;
  blocks.reserve(program.rules.size() + program.processes.size() + program.functions.size() + 1);
  for (const Rule& r : program.rules) blocks.push_back(&r.block);
  for (const Process& p : program.processes) blocks.push_back(&p.block);
  for (const Function& f : program.functions) blocks.push_back(&f.block);
  blocks.push_back(&program.globalsInit);
  return blocks;
}

}  // namespace meldvm
