// How checkpoints are opened: without HDF5 file locking (file systems without locks, ENOLCK),
// and read failures named by their real cause.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "base/errors.hpp"
#include "io/checkpoint_file.hpp"
#include "io/hdf5_handles.hpp"
#include "support/bad_checkpoints.hpp"
#include "support/files.hpp"
#include "support/synthetic_checkpoint.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {


TEST(CheckpointAccess, FilesAreOpenedWithoutHdf5FileLocking) {
  const h5::PropList fapl = h5::file_access_plist();
  hbool_t use_locking = true, ignore_when_disabled = false;
  ASSERT_GE(H5Pget_file_locking(fapl.get(), &use_locking, &ignore_when_disabled), 0);
  EXPECT_FALSE(use_locking);
  EXPECT_TRUE(ignore_when_disabled);
}

// HDF5's own lock is a flock(2); a file system without locks fails it with ENOLCK, another
// holder with EWOULDBLOCK. Either way, with locking off the checkpoint reads and is replaced.
TEST(CheckpointAccess, ReadAndReplaceWorkWhileAnotherHolderLocksTheFile) {
  const ScratchFolder scratch("locked");
  const fs::path file = scratch.path / "c.h5";
  const Checkpoint original = synthetic_checkpoint();
  write_checkpoint(file, original);
  const int fd = ::open(file.c_str(), O_RDWR | O_CLOEXEC);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  EXPECT_EQ(checkpoint_read_error(file), "(no InputError)");
  EXPECT_NO_THROW(write_checkpoint(file, original));
  EXPECT_EQ(checkpoint_read_error(file), "(no InputError)");
  ::flock(fd, LOCK_UN);
  ::close(fd);
}

TEST(CheckpointAccess, ReadFailuresNameTheirRealCause) {
  const ScratchFolder scratch("causes");
  const fs::path& dir = scratch.path;

  const fs::path missing = dir / "missing.h5";
  EXPECT_EQ(checkpoint_read_error(missing), missing.string() + ": no such checkpoint file: No such file or directory");

  const fs::path folder = dir / "folder.h5";
  fs::create_directory(folder);
  EXPECT_EQ(checkpoint_read_error(folder), folder.string() + ": not a regular file (Is a directory)");

  const fs::path fifo = dir / "fifo.h5";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  EXPECT_EQ(checkpoint_read_error(fifo), fifo.string() + ": not a regular file (a FIFO, socket or device)");

  const fs::path text = dir / "text.h5";
  write_file(text, "not hdf5 at all");
  EXPECT_EQ(checkpoint_read_error(text), text.string() + ": not an HDF5 file or truncated (no HDF5 signature at its start)");

  // A valid start and a cut-off rest: HDF5 itself refuses it.
  write_checkpoint(dir / "valid.h5", synthetic_checkpoint());
  const fs::path cut = dir / "cut.h5";
  write_file(cut, read_file(dir / "valid.h5").substr(0, 600));
  EXPECT_EQ(checkpoint_read_error(cut).rfind(cut.string() + ": ", 0), 0u) << checkpoint_read_error(cut);
  EXPECT_NE(checkpoint_read_error(cut), "(no InputError)");

  if (::geteuid() != 0) {  // root reads files whatever their mode
    const fs::path denied = dir / "denied.h5";
    fs::copy_file(dir / "valid.h5", denied);
    fs::permissions(denied, fs::perms::none);
    EXPECT_EQ(checkpoint_read_error(denied), denied.string() + ": cannot open checkpoint: Permission denied");
  }
}

}  // namespace
