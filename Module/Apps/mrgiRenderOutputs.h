// mrgiRenderOutputs: mrgi-render's outputs, all written or none left.
//
// Every -o path is checked before anything is rendered: a known extension,
// not given twice, not a directory, and its directory must take a new file
// (a probe file is created there and removed at once, which is the only
// check that also holds for root and for read-only file systems).
//
// Each image is first written to a staging file beside its output,
// "OUT.EXT.tmp-PID.EXT" (the image writers write that atomically in turn,
// through "STAGING.tmp-PID-N", mrgi_atomic_file.h). Only when every image
// is written are the staging files renamed onto the outputs; when one fails,
// every staging file is removed and the outputs already renamed in this run
// are removed too, so that a failed run leaves none of its outputs behind.
//
// SIGTERM, SIGINT and SIGHUP remove the staging files, their writers'
// temporaries and the outputs renamed so far (the handler only calls
// unlink() and _exit(), both async-signal-safe, on paths prepared before),
// then exit with 128 + the signal number.
#ifndef mrgiRenderOutputs_h
#define mrgiRenderOutputs_h

#include <functional>
#include <string>
#include <vector>

namespace mrgirender
{
class Outputs
{
public:
  // Installs the signal handlers (once per process).
  Outputs();
  // Removes what a run that did not Commit() left: staging files and their
  // temporaries.
  ~Outputs();
  Outputs(const Outputs&) = delete;
  Outputs& operator=(const Outputs&) = delete;

  // Checks every path (see above); false with `why` naming the path and the
  // problem. Call once, before rendering.
  bool Check(const std::vector<std::string>& paths, std::string& why);

  // The staging path the image for output `i` must be written to; its
  // extension is the output's, so writers that choose the format by
  // extension choose the same one.
  const std::string& StagingPath(size_t i) const;

  // Renames every staging file onto its output. On failure removes the
  // staging files and the outputs renamed so far; false with `why`.
  bool Commit(std::string& why);

  // Removes the staging files (after a failed write).
  void Abandon();

private:
  std::vector<std::string> Finals;
  std::vector<std::string> Stagings;
  bool Committed = false;
};
}

#endif
