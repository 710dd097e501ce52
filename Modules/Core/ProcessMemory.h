#ifndef vimlop_ProcessMemory_h
#define vimlop_ProcessMemory_h

#include <string>

/**
 * @file ProcessMemory.h
 * @brief The peak resident memory of this process's own address space.
 *
 * Not getrusage()'s ru_maxrss: Linux carries that across exec(), so a child
 * started by fork or posix_spawn reports at least its parent's peak at the
 * spawn. The address space's high-water mark (VmHWM in /proc/self/status)
 * starts again at exec.
 */
namespace vimlop
{

/// @brief VmHWM of /proc/self/status, MiB; negative when unknown (no /proc).
double peakResidentMiBOfThisProcess();

/// @brief The VmHWM line of a /proc/PID/status text, MiB; negative when it has none.
double peakResidentMiBFromStatus(const std::string& statusText);

} // namespace vimlop

#endif
