// Internal to libmpm/pem: one use of the Gmsh library, and the elements of its current model.
#pragma once
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "libmpm/pem/mesh_build.hpp"

namespace cleave::pem::detail {

// Gmsh keeps its model and options in process-wide state: uses are serialised (one mutex), and each
// starts from Gmsh's defaults (initialize without command line or configuration files, finalize on
// leaving, also through an exception), silent on the terminal and on one thread (same mesh every
// time). Gmsh's messages are logged so that a failure can quote them.
// Gmsh 4.8 also changes the process around it: OpenMP's thread count (to its General.NumThreads,
// which would leave the solver on one thread), LC_NUMERIC, the stack's soft limit (raised to the
// hard one), PATH and PYTHONPATH (its executable's folder appended). The session puts them back.
class GmshSession {
 public:
  GmshSession();
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

 private:
  struct Saved {
    int omp_threads = 1;
    std::string numeric_locale;
    bool have_stack_limit = false;
    unsigned long stack_soft = 0;
    std::optional<std::string> path, python_path;
  };
  void restore() const;

  std::unique_lock<std::mutex> lock_;
  Saved saved_;
};

// Gmsh's message for the exception being handled (Gmsh 4.8 throws std::string; its last error when
// the exception says nothing). Call inside a catch block only.
std::string gmsh_failure();

// Gmsh's last logged errors and warnings of this session, "; Gmsh says: ..." (empty when none): for
// an outcome Gmsh did not throw for (a shape it made no element of, a file it read nothing from).
std::string gmsh_complaints();

// Runs f(); a Gmsh failure becomes fail(Gmsh's message). SceneError and std::logic_error pass
// through (they are ours).
template <class F>
void gmsh_guarded(F&& f, const Fail& fail) {
  std::string message;
  try {
    f();
    return;
  } catch (const SceneError&) {
    throw;
  } catch (const std::logic_error&) {
    throw;
  } catch (...) {
    message = gmsh_failure();
  }
  fail(message);
}

// The elements of dimension `dim` of the given entities of Gmsh's current model, entity by entity in
// the order given (entity tag, region index), each entity's elements by type and then by Gmsh tag;
// points are every node of the model, ordered by Gmsh tag. An element kind PEM does not take (second
// order, prisms, pyramids) goes to fail(), named as Gmsh names it.
RawMesh gmsh_elements(int dim, const std::vector<std::pair<int, int32_t>>& entity_regions, const Fail& fail);

}  // namespace cleave::pem::detail
