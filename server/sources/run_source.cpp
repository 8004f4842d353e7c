#include "server/sources/run_source.hpp"

#include "common/run/run_names.hpp"

namespace fnet::sources {

namespace po = boost::program_options;

namespace {

// The input under the run id and ensemble the command line gives, where it gives them.
class NamedRun final : public FrameSource {
 public:
  NamedRun(std::unique_ptr<FrameSource> input, const std::string& run_id, const std::string& ensemble)
      : input_(std::move(input)), info_(input_->announcement()), run_id_(run_id) {
    if (!run_id.empty()) info_.run_id = run_id;
    if (!ensemble.empty()) info_.ensemble = ensemble;
  }
  const RunInfo& announcement() const override { return info_; }
  std::optional<RunFrame> next() override {
    std::optional<RunFrame> f = input_->next();
    if (f && !run_id_.empty()) {
      f->header.run_id = run_id_;
      f->frame.label = frame_label(run_id_, f->header.index);
    }
    return f;
  }

 private:
  std::unique_ptr<FrameSource> input_;
  RunInfo info_;
  std::string run_id_;
};

// `word` of each kind that announces its run, or of each that does not.
template <class Word>
std::vector<std::string> words_of(const std::vector<SourceKind>& kinds, bool announces, Word word) {
  std::vector<std::string> out;
  for (const SourceKind& kind : kinds)
    if (kind.announces == announces) out.push_back(word(kind));
  return out;
}

// " (a; b)", or nothing without notes.
std::string notes(const std::vector<std::string>& parts) {
  std::string out;
  for (const std::string& n : parts) out += (out.empty() ? " (" : "; ") + n;
  return out.empty() ? out : out + ")";
}

std::string value_of(const po::variables_map& vm, const char* name) {
  return vm.count(name) ? vm[name].as<std::string>() : std::string();
}

}  // namespace

std::string run_usage(const std::vector<SourceKind>& kinds) {
  std::string out;
  for (const SourceKind& kind : kinds)
    out += (out.empty() ? "(" : " | ") + kind_usage(kind) + (kind.announces ? "" : " --run-id R");
  return out + ")";
}

void add_run_options(const std::vector<SourceKind>& kinds, po::options_description& options) {
  add_source_options(kinds, options);
  const auto own = words_of(kinds, true, [](const SourceKind& k) { return "the " + k.name + "'s"; });
  const auto flags = words_of(kinds, false, [](const SourceKind& k) { return "--" + k.flags.front().name; });
  const auto without = words_of(kinds, false, [](const SourceKind& k) { return "a " + k.name; });
  std::vector<std::string> run_id_notes, ensemble_notes;
  if (!flags.empty()) run_id_notes.push_back("required with " + join_words(flags, "or"));
  if (!own.empty()) {
    run_id_notes.push_back("overrides " + join_words(own, "or"));
    ensemble_notes.push_back("overrides " + join_words(own, "or"));
  }
  if (!without.empty()) ensemble_notes.push_back(join_words(without, "or") + " has none");
  options.add_options()("run-id", po::value<std::string>(), ("run id" + notes(run_id_notes)).c_str())(
      "ensemble", po::value<std::string>(),
      ("the ensemble of realizations the run belongs to" + notes(ensemble_notes)).c_str());
}

std::unique_ptr<FrameSource> open_run(const std::vector<SourceKind>& kinds, const po::variables_map& vm) {
  const ChosenSource chosen = choose_source(kinds, vm);
  const std::string run_id = value_of(vm, "run-id"), ensemble = value_of(vm, "ensemble");
  if (!chosen.kind->announces && run_id.empty())
    throw po::error("--" + chosen.kind->flags.front().name + " needs --run-id");
  if (!run_id.empty())
    if (const std::string problem = run_id_problem(run_id); !problem.empty()) throw po::error("--run-id: " + problem);
  if (!ensemble.empty())
    if (const std::string problem = name_problem(ensemble, "ensemble name"); !problem.empty())
      throw po::error("--ensemble: " + problem);
  auto run = std::make_unique<NamedRun>(chosen.open(), run_id, ensemble);
  if (const std::string problem = run_id_problem(run->announcement().run_id); !problem.empty())
    throw po::error(problem);
  return run;
}

}  // namespace fnet::sources
