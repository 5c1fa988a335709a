!> Operating-system calls the driver needs (POSIX, through C interoperability):
!> create, rename and remove folders and files, list hidden entries of a
!> folder by pattern, process id and liveness, terminal test, signals (a
!> file size limit reported as a failed write; an interrupt that undoes a
!> case folder being written), host name and the flock(2) case locks
!> (visco2d_lock_glue.c).
module visco2d_system
  use, intrinsic :: iso_fortran_env, only: int8
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char, c_size_t, c_ptr, c_funptr, c_null_ptr, &
                                         c_null_funptr, c_intptr_t, c_f_pointer, c_associated, c_funloc
  implicit none
  private

  public :: make_directory, rename_path, remove_file, remove_directory, process_id, is_terminal
  public :: directory_exists, path_exists, remove_tree, process_alive, matching_paths, ignore_file_size_signal
  public :: path_t, get_argument
  public :: install_interrupt_cleanup, interrupt_cleanup_arm, interrupt_cleanup_restore, interrupt_cleanup_disarm
  public :: file_open_write, file_write, file_close
  public :: host_name, lock_take, lock_release, lock_close, interrupt_lock_arm, interrupt_lock_disarm, hold_interrupts

  !> One path of a list (`matching_paths`).
  type :: path_t
    character(:), allocatable :: path
  end type path_t

  !> POSIX glob_t: the fields read here come first in glibc and musl
  !> (count, vector, offset, flags); the rest is reserved room.
  type, bind(c) :: glob_t
    integer(c_size_t) :: path_count = 0
    type(c_ptr) :: paths = c_null_ptr
    integer(c_size_t) :: offset = 0
    integer(c_int) :: flags = 0
    type(c_ptr) :: reserved(16) = c_null_ptr
  end type glob_t

  !> SIGXFSZ (file size limit exceeded) on Linux and the BSDs.
  integer(c_int), parameter :: signal_file_size = 25
  !> SIGHUP, SIGINT, SIGTERM: the signals that end a run early (POSIX numbers).
  integer(c_int), parameter :: interrupt_signals(3) = [1_c_int, 2_c_int, 15_c_int]

  !> What an interrupt must undo while a case folder is being written: the
  !> files of the temporary folder and the folder, and a case folder moved
  !> aside (old -> final). Null-terminated paths, set before the signal can
  !> need them; the handler only calls unlink, rmdir, rename, signal and raise.
  integer, parameter :: cleanup_length = 4096
  integer, parameter :: cleanup_files = 5
  character(kind=c_char, len=cleanup_length), save :: cleanup_path(cleanup_files) = c_null_char
  character(kind=c_char, len=cleanup_length), save :: cleanup_old = c_null_char, cleanup_final = c_null_char
  logical, volatile, save :: cleanup_armed = .false., cleanup_restore_old = .false.
  !> The lock file of the case being run (removed by an interrupt: the lock itself ends with the process).
  character(kind=c_char, len=cleanup_length), save :: cleanup_lock = c_null_char
  logical, volatile, save :: cleanup_lock_armed = .false.

  interface
    integer(c_int) function c_mkdir(path, mode) bind(c, name='mkdir')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int), value :: mode
    end function c_mkdir
    integer(c_int) function c_rename(old, new) bind(c, name='rename')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: old(*), new(*)
    end function c_rename
    integer(c_int) function c_unlink(path) bind(c, name='unlink')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
    end function c_unlink
    integer(c_int) function c_rmdir(path) bind(c, name='rmdir')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
    end function c_rmdir
    integer(c_int) function c_getpid() bind(c, name='getpid')
      import :: c_int
    end function c_getpid
    integer(c_int) function c_kill(pid, signal) bind(c, name='kill')
      import :: c_int
      integer(c_int), value :: pid, signal
    end function c_kill
    integer(c_int) function c_isatty(fd) bind(c, name='isatty')
      import :: c_int
      integer(c_int), value :: fd
    end function c_isatty
    integer(c_int) function c_glob(pattern, flags, on_error, result) bind(c, name='glob')
      import :: c_int, c_char, c_funptr, glob_t
      character(kind=c_char), intent(in) :: pattern(*)
      integer(c_int), value :: flags
      type(c_funptr), value :: on_error
      type(glob_t), intent(inout) :: result
    end function c_glob
    subroutine c_globfree(result) bind(c, name='globfree')
      import :: glob_t
      type(glob_t), intent(inout) :: result
    end subroutine c_globfree
    integer(c_size_t) function c_strlen(text) bind(c, name='strlen')
      import :: c_size_t, c_ptr
      type(c_ptr), value :: text
    end function c_strlen
    type(c_funptr) function c_signal(signal, handler) bind(c, name='signal')
      import :: c_int, c_funptr
      integer(c_int), value :: signal
      type(c_funptr), value :: handler
    end function c_signal
    integer(c_int) function c_raise(signal) bind(c, name='raise')
      import :: c_int
      integer(c_int), value :: signal
    end function c_raise
    type(c_ptr) function c_fopen(path, mode) bind(c, name='fopen')
      import :: c_ptr, c_char
      character(kind=c_char), intent(in) :: path(*), mode(*)
    end function c_fopen
    integer(c_size_t) function c_fwrite(buffer, size, count, stream) bind(c, name='fwrite')
      import :: c_size_t, c_ptr
      type(*), intent(in) :: buffer(*)
      integer(c_size_t), value :: size, count
      type(c_ptr), value :: stream
    end function c_fwrite
    integer(c_int) function c_fclose(stream) bind(c, name='fclose')
      import :: c_int, c_ptr
      type(c_ptr), value :: stream
    end function c_fclose
    integer(c_int) function c_lock_take(path, text, holder, size, patient) bind(c, name='visco2d_lock_take')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*), text(*)
      character(kind=c_char), intent(out) :: holder(*)
      integer(c_int), value :: size, patient
    end function c_lock_take
    subroutine c_lock_release(fd, path) bind(c, name='visco2d_lock_release')
      import :: c_int, c_char
      integer(c_int), value :: fd
      character(kind=c_char), intent(in) :: path(*)
    end subroutine c_lock_release
    subroutine c_lock_close(fd) bind(c, name='visco2d_lock_close')
      import :: c_int
      integer(c_int), value :: fd
    end subroutine c_lock_close
    integer(c_int) function c_hold_interrupts(hold) bind(c, name='visco2d_hold_interrupts')
      import :: c_int
      integer(c_int), value :: hold
    end function c_hold_interrupts
    subroutine c_host_name(name, size) bind(c, name='visco2d_host_name')
      import :: c_int, c_char
      character(kind=c_char), intent(out) :: name(*)
      integer(c_int), value :: size
    end subroutine c_host_name
  end interface

  !> Write a file through C stdio, which reports every failed write and a
  !> failed close (the Fortran runtime may not, and may then keep the unit).
  interface file_write
    module procedure file_write_text, file_write_bytes
  end interface file_write

contains

  !> mkdir -p: create a folder and its missing parents. Returns 0 on success.
  integer function make_directory(path) result(status)
    character(*), intent(in) :: path
    integer :: i
    status = 0
    do i = 2, len(path)
      if (path(i:i) == '/' .and. path(i-1:i-1) /= '/') then
        if (.not. directory_exists(path(1:i-1))) status = c_mkdir(path(1:i-1)//c_null_char, int(o'755', c_int))
      end if
    end do
    if (.not. directory_exists(path)) status = c_mkdir(path//c_null_char, int(o'755', c_int))
    if (directory_exists(path)) status = 0
  end function make_directory

  logical function directory_exists(path)
    character(*), intent(in) :: path
    inquire(file=path//'/.', exist=directory_exists)
  end function directory_exists

  !> True if anything (file, folder, device) exists at the path.
  logical function path_exists(path)
    character(*), intent(in) :: path
    inquire(file=path, exist=path_exists)
  end function path_exists

  integer function rename_path(old, new) result(status)
    character(*), intent(in) :: old, new
    status = c_rename(old//c_null_char, new//c_null_char)
  end function rename_path

  integer function remove_file(path) result(status)
    character(*), intent(in) :: path
    status = c_unlink(path//c_null_char)
  end function remove_file

  integer function remove_directory(path) result(status)
    character(*), intent(in) :: path
    status = c_rmdir(path//c_null_char)
  end function remove_directory

  !> rm -rf of a folder (used only for folders this program names: older or
  !> stale copies of case folders). Each entry is first unlinked, which removes
  !> a file or a symbolic link (never followed); what cannot be unlinked is a
  !> folder, emptied the same way and removed.
  recursive subroutine remove_tree(path)
    character(*), intent(in) :: path
    type(path_t), allocatable :: entries(:)
    character(len=6), parameter :: patterns(3) = [character(len=6) :: '*', '.[!.]*', '..?*']   ! all but . and ..
    integer :: k, p, status
    if (c_unlink(path//c_null_char) == 0) return
    do p = 1, size(patterns)
      entries = matching_paths(path, trim(patterns(p)))
      do k = 1, size(entries)
        if (c_unlink(entries(k)%path//c_null_char) /= 0) call remove_tree(entries(k)%path)
      end do
    end do
    status = c_rmdir(path//c_null_char)
  end subroutine remove_tree

  integer function process_id()
    process_id = int(c_getpid())
  end function process_id

  !> True if a process with this id exists (kill(pid, 0); where that is refused,
  !> because the process belongs to another user, /proc/<pid> tells). Ids < 1 are never alive.
  logical function process_alive(pid) result(alive)
    integer, intent(in) :: pid
    character(len=16) :: text
    alive = .false.
    if (pid < 1) return
    alive = c_kill(int(pid, c_int), 0_c_int) == 0
    if (alive) return
    write(text, '(i0)') pid
    if (directory_exists('/proc/self')) then
      alive = directory_exists('/proc/'//trim(text))
    else
      alive = .true.                  ! no /proc: cannot tell "no such process" from "not ours"; keep
    end if
  end function process_alive

  !> This host's name (gethostname), with any character other than letters,
  !> digits, '-' and '.' replaced by '_' (it is part of folder names); 'unknown' if there is none.
  function host_name() result(name)
    character(:), allocatable :: name
    character(kind=c_char, len=256) :: buffer
    integer :: i, length
    call c_host_name(buffer, int(len(buffer), c_int))
    length = index(buffer, c_null_char) - 1
    if (length < 0) length = len(buffer)
    name = buffer(1:length)
    do i = 1, len(name)
      if (verify(name(i:i), 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-.') /= 0) name(i:i) = '_'
    end do
    if (len(name) == 0) name = 'unknown'
  end function host_name

  !> Take the flock(2) lock of the file `path` (created if missing) without
  !> waiting. status 0: this process holds it until lock_release(fd, path) or
  !> its end, and the file now holds `text` (unless text is ''); `holder` is
  !> what the file held before. status 1: another process holds it, `holder`
  !> is what the file says of it (its host and pid). status 2: the file cannot
  !> be created or locked, `holder` is the system's reason. `patient`: a lock
  !> held for less than 0.2 s (another run's check of it) is waited for.
  subroutine lock_take(path, text, fd, status, holder, patient)
    character(*), intent(in) :: path, text
    integer, intent(out) :: fd, status
    character(:), allocatable, intent(out) :: holder
    logical, intent(in) :: patient
    character(kind=c_char, len=512) :: buffer
    integer :: length
    fd = int(c_lock_take(path//c_null_char, text//c_null_char, buffer, int(len(buffer), c_int), &
                        merge(1_c_int, 0_c_int, patient)))
    length = index(buffer, c_null_char) - 1
    if (length < 0) length = len(buffer)
    holder = buffer(1:length)
    status = 0
    if (fd == -1) status = 1
    if (fd < -1) status = 2
  end subroutine lock_take

  !> Release a lock of lock_take: its file is removed, then closed.
  subroutine lock_release(fd, path)
    integer, intent(in) :: fd
    character(*), intent(in) :: path
    call c_lock_release(int(fd, c_int), path//c_null_char)
  end subroutine lock_release

  !> Release a lock of lock_take and leave its file in place.
  subroutine lock_close(fd)
    integer, intent(in) :: fd
    call c_lock_close(int(fd, c_int))
  end subroutine lock_close

  !> From now on an interrupt also removes this lock file (the case's lock).
  subroutine interrupt_lock_arm(path)
    character(*), intent(in) :: path
    cleanup_lock_armed = .false.
    cleanup_lock = c_text(path)
    cleanup_lock_armed = len(path) < cleanup_length
  end subroutine interrupt_lock_arm

  !> Hold SIGINT and SIGTERM (hold = .true.) until they are let through again
  !> (.false.): an interrupt that came meanwhile is then delivered.
  subroutine hold_interrupts(hold)
    logical, intent(in) :: hold
    integer(c_int) :: status
    status = c_hold_interrupts(merge(1_c_int, 0_c_int, hold))
  end subroutine hold_interrupts

  !> No lock file to remove on an interrupt.
  subroutine interrupt_lock_disarm()
    cleanup_lock_armed = .false.
  end subroutine interrupt_lock_disarm

  !> The paths matching a shell pattern (glob(3), sorted); none if nothing
  !> matches. `folder` is taken literally (its *, ? and [ are escaped) and
  !> `pattern` is a pattern for the names in it ('.*.partial.*').
  function matching_paths(folder, pattern) result(paths)
    character(*), intent(in) :: folder, pattern
    type(path_t), allocatable :: paths(:)
    type(glob_t) :: found
    type(c_ptr), pointer :: vector(:)
    character(kind=c_char, len=1), pointer :: characters(:)
    integer :: k, n, length, i
    allocate(paths(0))
    if (c_glob(escaped(folder)//'/'//pattern//c_null_char, 0_c_int, c_null_funptr, found) /= 0) then
      call c_globfree(found)
      return
    end if
    n = int(found%path_count)
    if (n > 0 .and. c_associated(found%paths)) then
      call c_f_pointer(found%paths, vector, [n])
      deallocate(paths)
      allocate(paths(n))
      do k = 1, n
        length = int(c_strlen(vector(k)))
        call c_f_pointer(vector(k), characters, [length])
        allocate(character(len=length) :: paths(k)%path)
        do i = 1, length
          paths(k)%path(i:i) = characters(i)
        end do
      end do
    end if
    call c_globfree(found)
  end function matching_paths

  !> A path with the glob(3) special characters escaped by a backslash.
  pure function escaped(path) result(text)
    character(*), intent(in) :: path
    character(:), allocatable :: text
    integer :: i
    text = ''
    do i = 1, len(path)
      if (index('*?[]\', path(i:i)) > 0) text = text//'\'
      text = text//path(i:i)
    end do
  end function escaped

  !> Ignore SIGXFSZ: a write past a file size limit (ulimit -f) then fails
  !> with an error the writer reports, instead of killing the process.
  subroutine ignore_file_size_signal()
    type(c_funptr) :: previous
    previous = c_signal(signal_file_size, transfer(1_c_intptr_t, c_null_funptr))   ! SIG_IGN = (handler) 1
  end subroutine ignore_file_size_signal

  !> On SIGHUP, SIGINT or SIGTERM, undo a case folder being written (see
  !> interrupt_cleanup_arm), then end as the signal would have (default action).
  subroutine install_interrupt_cleanup()
    type(c_funptr) :: previous
    integer :: k
    do k = 1, size(interrupt_signals)
      previous = c_signal(interrupt_signals(k), c_funloc(on_interrupt))
    end do
  end subroutine install_interrupt_cleanup

  !> From now on an interrupt removes these files (at most 4) and then the folder.
  subroutine interrupt_cleanup_arm(folder, files)
    character(*), intent(in) :: folder
    type(path_t), intent(in) :: files(:)
    integer :: k
    cleanup_armed = .false.
    cleanup_restore_old = .false.
    cleanup_path = c_null_char
    do k = 1, min(size(files), cleanup_files - 1)
      cleanup_path(k) = c_text(files(k)%path)
    end do
    cleanup_path(cleanup_files) = c_text(folder)
    cleanup_armed = len(folder) < cleanup_length
  end subroutine interrupt_cleanup_arm

  !> The case folder `final` has been moved to `old`: an interrupt now also moves it back.
  subroutine interrupt_cleanup_restore(old, final)
    character(*), intent(in) :: old, final
    cleanup_old = c_text(old)
    cleanup_final = c_text(final)
    cleanup_restore_old = len(old) < cleanup_length .and. len(final) < cleanup_length
  end subroutine interrupt_cleanup_restore

  !> Nothing left to undo.
  subroutine interrupt_cleanup_disarm()
    cleanup_armed = .false.
    cleanup_restore_old = .false.
  end subroutine interrupt_cleanup_disarm

  !> A path as a null-terminated C string ('' if too long: nothing is removed then).
  pure function c_text(path) result(text)
    character(*), intent(in) :: path
    character(kind=c_char, len=cleanup_length) :: text
    text = c_null_char
    if (len(path) < cleanup_length) text = path//c_null_char
  end function c_text

  !> The signal handler: async-signal-safe calls only.
  subroutine on_interrupt(signal) bind(c)
    integer(c_int), value :: signal
    type(c_funptr) :: previous
    integer(c_int) :: status
    integer :: k
    if (cleanup_armed) then
      do k = 1, cleanup_files
        if (cleanup_path(k)(1:1) == c_null_char) cycle
        if (k < cleanup_files) then
          status = c_unlink(cleanup_path(k))
        else
          status = c_rmdir(cleanup_path(k))
        end if
      end do
      if (cleanup_restore_old) status = c_rename(cleanup_old, cleanup_final)
    end if
    if (cleanup_lock_armed) status = c_unlink(cleanup_lock)
    previous = c_signal(signal, c_null_funptr)          ! SIG_DFL = (handler) 0
    status = c_raise(signal)
  end subroutine on_interrupt

  !> Create (replace) a file for writing; a null pointer if that fails.
  function file_open_write(path) result(stream)
    character(*), intent(in) :: path
    type(c_ptr) :: stream
    stream = c_fopen(path//c_null_char, 'wb'//c_null_char)
  end function file_open_write

  !> Write text (as it is: add new_line('a') for a line); 0 if all of it was written.
  integer function file_write_text(stream, text) result(status)
    type(c_ptr), intent(in) :: stream
    character(*), intent(in) :: text
    status = 0
    if (len(text) == 0) return
    if (c_fwrite(text, 1_c_size_t, int(len(text), c_size_t), stream) /= int(len(text), c_size_t)) status = 1
  end function file_write_text

  !> Write bytes; 0 if all of them were written.
  integer function file_write_bytes(stream, bytes) result(status)
    type(c_ptr), intent(in) :: stream
    integer(int8), intent(in) :: bytes(:)
    status = 0
    if (size(bytes) == 0) return
    if (c_fwrite(bytes, 1_c_size_t, int(size(bytes), c_size_t), stream) /= int(size(bytes), c_size_t)) status = 1
  end function file_write_bytes

  !> Close a file (this writes what stdio still holds); 0 if that worked. The stream is freed either way.
  integer function file_close(stream) result(status)
    type(c_ptr), intent(in) :: stream
    status = int(c_fclose(stream))
  end function file_close

  !> True if the file descriptor (2 = stderr) is a terminal.
  logical function is_terminal(fd)
    integer, intent(in) :: fd
    is_terminal = c_isatty(int(fd, c_int)) == 1
  end function is_terminal
  !> The command-line argument at `position`, whole (any length).
  subroutine get_argument(position, value)
    integer, intent(in) :: position
    character(:), allocatable, intent(out) :: value
    integer :: n
    call get_command_argument(position, length=n)
    allocate(character(len=n) :: value)
    call get_command_argument(position, value)
  end subroutine get_argument
end module visco2d_system
