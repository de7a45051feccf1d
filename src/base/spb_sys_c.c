/* spallbar: the system calls Fortran cannot make portably (struct stat's layout differs
 * between platforms). Used by src/base/spb_sys.f90 (sys_file_kind, sys_same_file, sys_lock_held,
 * sys_write_trouble). */
#define _DEFAULT_SOURCE   /* flock(2) under -std=c99 */
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

/* What path names, following links: -1 nothing (or not reachable), 0 a regular file,
 * 1 a folder, 2 anything else (a FIFO, a device, a socket). */
static int file_kind(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0) return -1;
    if (S_ISREG(st.st_mode)) return 0;
    if (S_ISDIR(st.st_mode)) return 1;
    return 2;
}

/* Whether two paths name the same existing file, following links: the same device and
 * inode (a hard link, a symbolic link or another spelling of the path). 0 when either is
 * missing. */
int spb_same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    if (stat(a, &sa) != 0 || stat(b, &sb) != 0) return 0;
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

/* Whether another open file holds a flock(2) lock on path (shared or exclusive: an HDF5
 * reader such as h5py or ParaView holds one, a spallbar run holds PREFIX.lock): an
 * exclusive non-blocking lock on a descriptor of our own is refused. 0 when path is
 * missing or unreadable, or nobody holds it. The test takes nothing: its lock goes with the
 * descriptor at once. */
static int lock_held(const char *path)
{
    int fd = open(path, O_RDONLY);
    int held;
    if (fd < 0) return 0;
    held = flock(fd, LOCK_EX | LOCK_NB) != 0;
    close(fd);
    return held;
}

/* Why a file system may refuse writes, for a message: 1 it is mounted read-only, 2 no
 * block is free for an unprivileged user (full, or the quota's file system is), 0 neither
 * shows (statvfs(3); -1 when path's file system cannot be asked). */
static int fs_state(const char *path)
{
    struct statvfs sv;
    if (statvfs(path, &sv) != 0) return -1;
    if (sv.f_flag & ST_RDONLY) return 1;
    if (sv.f_bavail == 0) return 2;
    return 0;
}

/* One entry for the questions about a path (one interface on the Fortran side): what 0
 * file_kind, 1 lock_held, 2 fs_state; -2 for another question. */
int spb_path_query(const char *path, int what)
{
    switch (what) {
    case 0: return file_kind(path);
    case 1: return lock_held(path);
    case 2: return fs_state(path);
    default: return -2;
    }
}
