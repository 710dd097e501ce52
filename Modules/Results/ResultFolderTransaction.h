#ifndef vimlop_ResultFolderTransaction_h
#define vimlop_ResultFolderTransaction_h

#include <string>

namespace vimlop
{

/**
 * @brief Writes a result folder as one step: the folder a user sees is the
 * old one or the complete new one, never a mix and never half of one.
 *
 * The constructor, called before the work starts, checks the folder, takes
 * a lock and creates a staging folder beside it, `<folder>.partial`. Every
 * file is written there; commit() flushes them to disk and renames the
 * staging folder onto the folder in one step (exchanging it with an old one,
 * which is then removed). Destroying a transaction that was not committed
 * removes the staging folder, unless keepStaging() was called (an output
 * failed and the poses already written must not be lost). A process killed
 * outright leaves its staging folder; the next run into the same folder
 * removes it and says so.
 *
 * The lock is `<folder>.lock`, held with flock() for the transaction's life,
 * so it dies with its process: a second run into the same folder fails at
 * once, naming the process that writes it.
 */
class ResultFolderTransaction
{
public:
  /// @brief What to do with a folder that already exists.
  enum class Existing
  {
    /// Refuse: "exists; choose another --out or add --force to replace it".
    Refuse,
    /// Replace it whole on commit() (--force). Only an empty folder or a
    /// VIMLOP result folder (it holds result.json or registered-poses.json)
    /// or export folder (vimlop-export.json)
    /// is replaced; anything else is refused, so a mistyped --out cannot
    /// remove a user's folder.
    Replace
  };

  /**
   * @brief Checks `folder`, locks it and creates the staging folder.
   * @throws vimlop::Error naming the folder: it exists (Refuse), it is not a
   * result folder (Replace), another process holds the lock, or the staging
   * folder cannot be created. Progress notes (a stale staging folder
   * removed) go to `note` when it is given.
   */
  ResultFolderTransaction(
    const std::string& folder, Existing existing, std::string* note = nullptr);
  ~ResultFolderTransaction();
  ResultFolderTransaction(const ResultFolderTransaction&) = delete;
  ResultFolderTransaction& operator=(const ResultFolderTransaction&) = delete;

  /// @brief The folder every file goes to until commit().
  const std::string& stagingFolder() const { return this->Staging; }
  /// @brief The folder the result is committed to.
  const std::string& folder() const { return this->Folder; }

  /**
   * @brief Flushes every file and folder of the staging folder to disk and
   * puts it in place of the folder in one rename; removes the old folder
   * and the lock.
   * @throws vimlop::Error when a flush or the rename fails (the staging
   * folder is then kept, and named).
   */
  void commit();

  /// @brief Keeps the staging folder when the transaction ends uncommitted.
  void keepStaging() { this->Keep = true; }

private:
  std::string Folder;
  std::string Staging;
  std::string LockPath;
  int LockFd = -1;
  bool Committed = false;
  bool Keep = false;
};

} // namespace vimlop

#endif
