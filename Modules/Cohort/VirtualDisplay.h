#ifndef vimlop_VirtualDisplay_h
#define vimlop_VirtualDisplay_h

#include <memory>
#include <string>

namespace vimlop
{

class ChildProcess;

/**
 * @brief A private X display (Xvfb) for the rows of a cohort that render
 * with VTK, which here needs an X display even offscreen. Cluster nodes
 * have none: a cohort runner starts one server and every row it runs shares
 * it through DISPLAY, set in this process while the object lives.
 *
 * Xvfb picks a free display number itself (-displayfd), so runners on one
 * machine never race for one; -noreset keeps it up between rows (an X server
 * resets when its last client leaves, which VTK does not survive). It is
 * stopped with the object, and killed with this process if that is killed.
 */
class VirtualDisplay
{
public:
  /**
   * @brief Starts Xvfb and sets DISPLAY; waits at most `timeoutS` for it.
   * @throws vimlop::Error when Xvfb is missing, fails or does not answer,
   * with what it said.
   */
  explicit VirtualDisplay(double timeoutS = 20.0);
  /// @brief Stops the server and restores DISPLAY (unset).
  ~VirtualDisplay();
  VirtualDisplay(const VirtualDisplay&) = delete;
  VirtualDisplay& operator=(const VirtualDisplay&) = delete;

  /// @brief The display's name, ":N".
  const std::string& name() const { return this->Name; }

private:
  std::unique_ptr<ChildProcess> Server;
  std::string Name;
};

} // namespace vimlop

#endif
