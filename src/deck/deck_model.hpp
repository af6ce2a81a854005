// DeckModel: one structure built and driven by a deck: the Model and its Analysis,
// the deck's named things (sections, load functions, surfaces, driven spindles), and its
// result file. The named things are members, so they live and die with the model.
#pragma once

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/model.hpp"
#include "elements/tread_beam.hpp"
#include "io/result_file.hpp"
#include "deck/deck_session.hpp"
#include "solvers/analysis.hpp"
#include "tire/tire_builder.hpp"
#include "tire/wheel_axes.hpp"
#include "vehicle/spindle_exchange.hpp"

namespace tirefe {
class RigidSurface;
class TireSpindle;
}  // namespace tirefe

namespace tirefe::macros {

class DeckModel {
 public:
  DeckModel(std::string title, DeckSession& session);
  ~DeckModel();

  const std::string& title() const { return title_; }
  /// Counted from 1 in the order the deck creates its models.
  int index() const { return index_; }
  /// This process writes the model's result file and solves it in a vehicle (see DeckProcesses).
  bool owned() const { return session_.processes.owns(index_); }
  /// Another process advanced this model ('how' says by what): this copy is stale, and
  /// every later macro on it is refused with that message.
  void mark_advanced_elsewhere(const std::string& how);
  const std::string& stale() const { return stale_; }

  /// Marks the model busy for a scope: a macro on it runs, or a vehicle steps it. A Lua
  /// function the model calls back meanwhile (a load function's 'fn') must not change or
  /// step it, so every macro on a busy model is refused (check_model).
  class Busy {
   public:
    Busy(DeckModel& deck, std::string what);
    ~Busy() { deck_.busy_with_ = std::move(outer_); }
    Busy(const Busy&) = delete;
    Busy& operator=(const Busy&) = delete;

   private:
    DeckModel& deck_;
    std::string outer_;
  };
  /// What keeps the model busy ("model:step", "tirefe.vehicle"), or "".
  const std::string& busy_with() const { return busy_with_; }
  /// The most a deck's models hold together (docs/decks.md, Limits): a loop adding nodes,
  /// elements or models without end stops here with its deck line, before the memory runs
  /// out (a model's memory lies outside the Lua memory bound).
  static constexpr int kMaxNodes = 1000000;
  static constexpr int kMaxElements = 1000000;
  static constexpr int kMaxModels = 1000;
  /// Whether the session's live models hold at most kMaxNodes nodes and kMaxElements elements.
  bool fits() const;
  /// Throws ModelError if they hold more.
  void check_size() const;

  Model& model() { return model_; }
  Analysis& analysis() { return analysis_; }
  DeckSession& session() { return session_; }

  void define_section(const std::string& name, const BeamSection& section);
  const BeamSection& section(const std::string& name) const;
  void define_load_function(const std::string& name, LoadFunction function);
  int load_function(const std::string& name) const;
  /// A named rigid surface (model:surface); contact blocks share it.
  bool has_surface(const std::string& name) const { return surfaces_.count(name) > 0; }
  /// ModelError if the name is taken.
  void define_surface(const std::string& name, std::shared_ptr<const RigidSurface> surface);
  /// ModelError naming the defined surfaces if there is none of that name.
  std::shared_ptr<const RigidSurface> surface(const std::string& name) const;
  /// The spindle driven at 'node' (0-based; model:spindle_force, tirefe.vehicle), or null.
  TireSpindle* driven_spindle(int node);
  /// Starts driving the spindle at 'node' (none driven there yet).
  TireSpindle& drive_spindle(int node, SpinMode spin);
  /// The model calls back into the deck's Lua state (a load function given as a Lua
  /// function): it must then be solved on the deck's thread only.
  void note_lua_callback() { calls_lua_ = true; }
  bool calls_lua() const { return calls_lua_; }

  /// Opens the result file (a relative path is taken inside the session's output folder);
  /// in a process that does not own the model, a discarded one (no file is created).
  /// Without views_during_run the frames' views are left to `tirefe --views FILE`.
  void open_output(const std::string& file, int field_interval, double field_time_interval = 0.0,
                   bool views_during_run = true);
  io::ResultFile* output() { return output_.get(); }
  /// The result file, opened under a default name if the deck named none.
  io::ResultFile& output_or_default();
  /// Hands 'describe' the result file once it is open (at once if it is): what the file
  /// shows besides the mesh, such as a tire's rim or a surface to draw.
  void describe_output(std::function<void(io::ResultFile&)> describe);

  /// Advances the analysis; the first step opens the default output if none is open.
  /// Restarting, it skips the time before the checkpoint and loads the checkpoint when it gets there.
  const std::vector<StepRecord>& advance(double duration);

  /// Writes a checkpoint of the run now (a relative path lands in the output folder).
  void write_checkpoint(const std::string& file);
  /// Writes one after every 'steps' accepted steps and after 'minutes' of wall time (0: not by that measure).
  void schedule_checkpoints(const std::string& file, int steps, double minutes);
  /// Refuses 'what' while a restart is skipping time whose state it does not have.
  void require_state(const std::string& what) const;

  /// A tire built by model:tire, by its name (model:tire_contact finds its tread there).
  void define_tire(const Tire& tire);
  /// ModelError naming the model's tires if there is none of that name.
  const Tire& tire(const std::string& name) const;

  /// A tire's heading (model:tire{ heading }), by its spindle node: the wheel axes of its
  /// spindle forces. One result file states one heading, so a model's tires share it.
  void set_wheel_heading(int spindle, Heading heading);
  /// The heading of the tire whose spindle is 'node'; ModelError if it is no tire's spindle.
  Heading wheel_heading(int node) const;

 private:
  /// The progress line, and with --verbose one line on standard output.
  void report_step(const StepRecord& record) const;
  /// "model 2 ('rear tire')", for messages.
  std::string described() const;
  /// The checkpoint's path in the output folder, claimed for this model's checkpoints.
  std::string checkpoint_path(const std::string& file);
  // What this model's files are, claimed under these names in the session.
  std::string result_purpose() const;
  std::string checkpoint_purpose() const;
  std::string xdmf_purpose() const;
  void load_checkpoint();

  std::string title_;
  DeckSession& session_;
  Model model_;
  Analysis analysis_;
  std::map<std::string, BeamSection> sections_;
  std::map<std::string, int> load_functions_;
  std::map<std::string, std::shared_ptr<const RigidSurface>> surfaces_;
  std::map<int, std::unique_ptr<TireSpindle>> spindles_;  // by 0-based node; declared after analysis_, which they drive
  std::map<int, Heading> wheel_headings_;                 // by spindle node
  std::map<std::string, Tire> tires_;                     // by name
  std::unique_ptr<io::ResultFile> output_;
  std::vector<std::function<void(io::ResultFile&)>> output_descriptions_;  // until it opens
  bool calls_lua_ = false;
  int index_;  // counted from 1 in the order the deck creates its models
  std::shared_ptr<const Checkpoint> restart_;
  bool skipped_steps_ = false;
  std::string checkpoint_file_;
  int checkpoint_steps_ = 0;
  double checkpoint_minutes_ = 0.0;
  std::chrono::steady_clock::time_point last_checkpoint_ = std::chrono::steady_clock::now();
  std::vector<StepRecord> no_records_;
  std::string stale_;
  std::string busy_with_;
};

}  // namespace tirefe::macros
