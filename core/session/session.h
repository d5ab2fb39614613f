// Session: the editing model — one scene, many views, one history (seed 4.2,
// 5.2.5).
//
//   language view ──UpdateText(text)──┐            ┌──▶ every view: TextChanged(edits)
//   graphical view ─SetParameter(...)─┼─▶ Session ─┼──▶ every view: SceneChanged(changes)
//   host / CLI ─────Simulate()────────┘    │       └──▶ every view: Simulated()
//                                          ▼
//        text ─lang─▶ Scene ─Diff─▶ changes ─▶ incremental simulate
//
// * Update from text re-evaluates the script and classifies every element as
//   unchanged, modified, added, removed or renamed (named elements by name;
//   unnamed ones — forces, links — by where their command sits in the text,
//   then by content).  Errors are reported with spans; the valid part still
//   applies.
// * A parameter is graphically editable iff its element's command ran once and
//   the word is a literal number or vector (seed 4.2.2).  A graphical edit
//   becomes the minimal change of that literal — comments and formatting stay
//   — reported as byte ranges of the old text (LSP style, offsets in bytes of
//   UTF-8 text) with line and column.
// * Simulate is incremental.  When only bodies' initial values changed, the
//   equations, their compiled tapes and every unaffected component's results
//   are kept: the components holding those bodies' variables restart, with
//   everything that reads them and (through the collision monitor) everything
//   that collided with them afterwards.  Any other change forms the equations
//   anew and carries over the results of every component whose equations and
//   inputs are unchanged (carry.cc).  Either way the result equals a
//   from-scratch run bit for bit.
// * Undo and redo cover text and graphical edits alike (they are the same
//   thing: a new text).  Consecutive graphical edits of one parameter with
//   nothing in between — the steps of one handle drag — are one undo step;
//   a Simulate (the drag's end) or any other change closes it.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/pipeline/pipeline.h"
#include "core/scene/scene.h"

namespace asgard::session {

// Replace bytes [begin, end) of the previous text with `text`.  Line and
// column (1-based, in bytes) locate begin and end in the previous text.
struct TextEdit {
  int begin = 0;
  int end = 0;
  std::string text;
  int line = 1, column = 1, end_line = 1, end_column = 1;
};

enum class Change : uint8_t { kUnchanged, kModified, kAdded, kRemoved, kRenamed };
const char* ChangeName(Change c);

struct ElementChange {
  scene::ElementKind kind = scene::ElementKind::kBody;
  Change change = Change::kUnchanged;
  std::string name;      // the new name (or the old one when removed)
  std::string old_name;  // when renamed
  int old_index = -1;    // index among the elements of its kind, old scene
  int new_index = -1;    // ... new scene
};

// A parameter a graphical view may show or edit.
struct Parameter {
  scene::ElementKind kind = scene::ElementKind::kBody;
  std::string element;  // name, or kind#index for unnamed elements
  std::string param;    // option name without the dash
  std::string value;    // its text
  scene::SourceSpan span;
  bool editable = false;
  std::string reason;  // why not, when not
};

// An element as a graphical view addresses it, and whether its command can be
// edited in place (an option not written yet is then appended to it).
struct ElementInfo {
  scene::ElementKind kind = scene::ElementKind::kBody;
  std::string element;  // name, "simulator", or kind#index
  bool editable = false;
  std::string reason;  // why not, when not
  // What DeleteElement removes with it (the elements naming a body or
  // trajectory it removes, transitively), in the order it lists them.
  std::vector<std::string> deleted_with;
};

// A body's initial value that a trajectory sets at the start of the run, as
// the equations override it (-state pos: position and velocity; rot:
// rotation and spin; dpos: velocity; drot: spin; over [-from, -to), default
// the first to the last knot): a graphical view shows its handle read-only.
struct PrescribedInitial {
  std::string body;
  std::string param;   // init_pos, init_dpos, init_rot or init_drot
  std::string reason;  // "trajectory T prescribes its position from t = 0 to 2"
};

class SessionView {
 public:
  virtual ~SessionView() = default;
  virtual void TextChanged(const std::vector<TextEdit>& /*edits*/, const std::string& /*text*/) {}
  virtual void SceneChanged(const std::vector<ElementChange>& /*changes*/) {}
  virtual void Simulated() {}
};

struct SimulateStats {
  bool rebuilt = false;  // equations formed anew (not incremental)
  int components = 0;
  int components_reset = 0;  // restarted from t0 (directly or as readers)
  long steps = 0;            // steps this call took
  double seconds = 0.0;
};

struct EditResult {
  bool ok = false;
  std::string error;
  std::vector<TextEdit> edits;
  // DeleteElement: the other elements removed with it (their keys).
  std::vector<std::string> removed;
};

class Session {
 public:
  explicit Session(std::string text, pipeline::RunOptions options = {});
  ~Session();

  const std::string& text() const { return text_; }
  const scene::Scene& scene() const { return scene_; }
  std::vector<scene::Diagnostic> diagnostics() const;

  // The language view's "Update": adopt `text` as the scene.
  std::vector<ElementChange> UpdateText(const std::string& text);

  // Graphical edits.  `element` is a name, or kind#index for unnamed
  // elements ("force#0", "link#1"); `param` an option ("init_pos", "offset",
  // "x", "points" ...).  Values are numbers (a vector's components in order).
  EditResult SetParameter(const std::string& element, const std::string& param,
                          const std::vector<double>& values);
  // A braced word replaced whole (a shape_set's -desc from the shape
  // editor): `text` becomes `{text}`; refused unless the word is braced
  // and `text` keeps it one word.  Consecutive calls for one parameter are
  // one undo step, as a drag's SetParameter calls are.
  EditResult SetWord(const std::string& element, const std::string& param, const std::string& text);
  // Inserts a well-formatted command after the last command of its kind (or
  // at the end), or deletes an element's command.  Deleting a body also
  // deletes the forces, torques, links, trajectories and views that name it
  // (and a trajectory the links and views along it), all as one undo step;
  // it is refused when one of them cannot be deleted (made in a loop ...).
  EditResult CreateElement(const std::string& command);
  EditResult DeleteElement(const std::string& element);
  std::vector<Parameter> Parameters() const;
  std::vector<ElementInfo> ElementInfos() const;
  // From the evaluated scene (computed times and points count as well as
  // literal ones); the first trajectory that sets a value gives the reason.
  std::vector<PrescribedInitial> PrescribedInitials() const;

  // Simulates incrementally (see above).  False when the solver fails.
  bool Simulate(const std::function<void(double)>& progress = {});
  const pipeline::Run* run() const { return run_.get(); }
  const SimulateStats& last_stats() const { return stats_; }

  bool Undo();
  bool Redo();
  bool CanUndo() const { return history_index_ > 0; }
  bool CanRedo() const { return history_index_ + 1 < history_.size(); }

  int AddView(SessionView* view);
  void RemoveView(int id);

 private:
  std::vector<ElementChange> Adopt(const std::string& text, bool record);
  EditResult ApplyEdits(std::vector<TextEdit> edits);
  void FullRun(const std::function<void(double)>& progress);
  // Forms the equations anew but carries over every component whose
  // equations and inputs are unchanged (carry.cc).
  void CarryOverRun(const std::function<void(double)>& progress);

  std::string text_;
  scene::Scene scene_;
  pipeline::RunOptions options_;
  std::unique_ptr<pipeline::Run> run_;
  // Bodies whose initial state changed since the last simulation, and
  // whether anything else changed.
  std::vector<std::string> dirty_bodies_;
  bool structure_dirty_ = true;
  SimulateStats stats_;
  std::vector<std::string> history_;
  size_t history_index_ = 0;
  std::vector<std::pair<int, SessionView*>> views_;
  std::vector<TextEdit> pending_edits_;  // the edits of a graphical change
  // The parameter ("element\0param") of the graphical edit in progress and
  // of the one that made the newest history entry (empty: none open).
  std::string pending_key_, open_key_;
  int next_view_ = 1;
};

// Change analysis between two evaluations of a scene (exposed for tests).
std::vector<ElementChange> Diff(const scene::Scene& before, const std::string& before_text,
                                const scene::Scene& after, const std::string& after_text);

// Fills line and column of an edit from the text it applies to.
void Locate(TextEdit& edit, const std::string& text);

}  // namespace asgard::session
