#include "scenario/output_section.h"

#include "scenario/limits.h"

namespace cosim::orchestrator {

namespace fs = std::filesystem;

const std::vector<KeySpec>& OutputSection::keys() {
  static const std::vector<KeySpec> k = {
      {"folder", "runs/NAME",
       "run folder, relative to where cosim runs, without '..'; an existing one is never "
       "overwritten (a -2, -3 suffix is added). Any other folder: cosim run -o FOLDER, which is "
       "that run's or none: an existing folder that is not empty is refused, saying what to do "
       "(another -o, remove it, --overwrite, or cosim resume when it holds a checkpoint)"},
      {"interval", "0", "particle snapshot interval [s]; 0 = every coupling step"},
  };
  return k;
}

std::string unsafeNameReason(const std::string& name) {
  if (name.empty()) return "is empty";
  if (name.size() > limits::kMaxNameLength)
    return "is longer than " + std::to_string(limits::kMaxNameLength) + " characters";
  if (name.front() == '.' || name.front() == '-') return "starts with '" + name.substr(0, 1) + "'";
  for (char ch : name) {
    const bool ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') ||
                    (ch >= '0' && ch <= '9') || ch == '.' || ch == '_' || ch == '-' || ch == '+';
    if (!ok) {
      const auto u = static_cast<unsigned char>(ch);
      return u >= 0x20 && u < 0x7f ? "contains '" + std::string(1, ch) + "'"
                                   : "contains the byte " + std::to_string(u);
    }
  }
  return "";
}

OutputSection parseOutput(const YAML::Node& o, const Context& ctx, const std::string& name) {
  OutputSection out;
  out.folder = fs::current_path() / "runs" / name;
  if (!ctx.section(o, "output", "{ folder: ..., interval: SECONDS }")) return out;
  ctx.allowOnly(o, "output", OutputSection::keys());
  if (o["folder"]) {
    const std::string text = ctx.text(o["folder"], "output.folder");
    const fs::path f = text;
    if (f.is_absolute()) {
      ctx.fail(o["folder"], "output.folder",
               "'" + text +
                   "' is absolute; a scenario writes below the folder cosim runs in (give a "
                   "relative folder, or choose any folder with cosim run -o)");
    }
    for (const auto& part : f) {
      const std::string s = part.string();
      if (s.empty()) continue;  // trailing '/'
      if (const std::string why = unsafeNameReason(s); !why.empty()) {
        ctx.fail(o["folder"], "output.folder",
                 "'" + text + "': the part '" + s + "' " + why +
                     "; use letters, digits, '.', '_', '-', '+' and no '..' (cosim run -o "
                     "chooses any folder)");
      }
    }
    if (f.empty()) ctx.fail(o["folder"], "output.folder", "is empty; give a folder name");
    out.folder = fs::current_path() / f;
  }
  if (o["interval"]) {
    out.interval = ctx.number(o["interval"], "output.interval");
    if (out.interval < 0)
      ctx.fail(o["interval"], "output.interval", "must be >= 0 seconds (0 = every coupling step)");
  }
  return out;
}

}  // namespace cosim::orchestrator
