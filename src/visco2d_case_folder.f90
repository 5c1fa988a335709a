!> The case folders of a run: the output root checked (and cleared of what
!> dead runs left) before any deck runs, the lock of a case held while it
!> runs (a second run of the same case into the same root fails instead of
!> overwriting the first), and the files of one case written under a
!> temporary name and renamed into place only when every file is complete,
!> so a failed deck never leaves half-written output.
module visco2d_case_folder
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: integer_text
  use visco2d_deck, only: deck_t
  use visco2d_record, only: record_t
  use visco2d_output, only: write_summary, write_history, write_results_h5, write_pressure
  use visco2d_listing, only: write_listing
  use visco2d_xdmf, only: write_results_xdmf
  use visco2d_system, only: make_directory, rename_path, remove_file, remove_directory, process_id, &
                            directory_exists, path_exists, remove_tree, process_alive, matching_paths, path_t, &
                            interrupt_cleanup_arm, interrupt_cleanup_restore, interrupt_cleanup_disarm, &
                            host_name, lock_take, lock_release, lock_close, interrupt_lock_arm, interrupt_lock_disarm, &
                            hold_interrupts
  implicit none
  private

  public :: write_case_folder, prepare_output_root, remove_stale_folders, lock_case, unlock_case, case_lock_t

  !> The lock of a case while it runs: an flock(2) on OUT/.<case>.lock, which
  !> names its holder ("process <pid> on host <host>").
  type :: case_lock_t
    integer :: fd = -1                             !< the lock file's descriptor (-1: not held)
    character(:), allocatable :: path              !< OUT/.<case>.lock
    type(path_t), allocatable :: created(:)        !< folders made for it (the root and missing parents, deepest first)
  end type case_lock_t

  !> The files of a case folder.
  character(len=*), parameter :: case_files(6) = [character(len=12) :: 'summary.txt', 'history.csv', &
                                                  'listing.txt', 'results.h5', 'results.xmf', 'pressure.csv']

contains

  !> Write the files of a case (case_files) into a temporary folder in out_root, then
  !> move it into place (the previous case folder is replaced only then). On
  !> any failure the temporary folder is removed and an existing case folder is
  !> left as it was.
  subroutine write_case_folder(path, out_root, case_name, deck, effects, record, error)
    character(*), intent(in) :: path, out_root, case_name, effects
    type(deck_t), intent(in) :: deck
    type(record_t), intent(in) :: record
    type(error_t), allocatable, intent(inout) :: error
    character(:), allocatable :: final_dir, temporary_dir, old_dir, file
    type(error_t), allocatable :: failure
    logical :: replaced

    final_dir = out_root//'/'//case_name
    temporary_dir = out_root//'/.'//case_name//'.partial.'//owner_tag()
    old_dir = out_root//'/.'//case_name//'.old.'//owner_tag()
    call interrupt_cleanup_arm(temporary_dir, file_paths(temporary_dir))   ! SIGINT/SIGTERM/SIGHUP undo what follows
    call write_and_move(error)
    call interrupt_cleanup_disarm()

  contains

    !> The files into the temporary folder, then the folder into place.
    subroutine write_and_move(error)
      type(error_t), allocatable, intent(inout) :: error
      if (make_directory(temporary_dir) /= 0) then
        call set_error(error, 'cannot create the output folder '//temporary_dir//'; nothing was written', file=path)
        return
      end if
      file = 'summary.txt'
      call write_summary(temporary_dir//'/'//file, record, failure)
      if (.not. allocated(failure)) then
        file = 'history.csv'
        call write_history(temporary_dir//'/'//file, record, failure)
      end if
      if (.not. allocated(failure)) then
        file = 'listing.txt'
        call write_listing(temporary_dir//'/'//file, case_name, deck, effects, record, failure)
      end if
      if (.not. allocated(failure)) then
        file = 'results.h5'
        call write_results_h5(temporary_dir//'/'//file, case_name, deck, record, failure)
      end if
      if (.not. allocated(failure) .and. allocated(record%pressure%columns)) then
        file = 'pressure.csv'
        call write_pressure(temporary_dir//'/'//file, record, failure)
      end if
      if (.not. allocated(failure)) then
        file = 'results.xmf'
        call write_results_xdmf(temporary_dir//'/'//file, deck, record, failure)
      end if
      if (allocated(failure)) then
        call discard(temporary_dir)
        call set_error(error, 'cannot write '//final_dir//'/'//file//': '//failure%message//'; no output was kept', &
                       file=path)
        return
      end if
      replaced = directory_exists(final_dir)
      if (replaced) then
        if (rename_path(final_dir, old_dir) /= 0) then
          call discard(temporary_dir)
          call set_error(error, 'cannot replace the existing output folder '//final_dir, file=path)
          return
        end if
        call interrupt_cleanup_restore(old_dir, final_dir)
      end if
      if (rename_path(temporary_dir, final_dir) /= 0) then
        call discard(temporary_dir)
        if (replaced) then
          if (rename_path(old_dir, final_dir) /= 0) continue    ! the old folder stays as old_dir
        end if
        call set_error(error, 'cannot create output folder '//final_dir, file=path)
        return
      end if
      call interrupt_cleanup_disarm()
      if (directory_exists(old_dir)) call remove_tree(old_dir)
    end subroutine write_and_move
  end subroutine write_case_folder

  !> The paths of the files of a case folder.
  function file_paths(folder) result(paths)
    character(*), intent(in) :: folder
    type(path_t), allocatable :: paths(:)
    integer :: k
    allocate(paths(size(case_files)))
    do k = 1, size(case_files)
      paths(k)%path = folder//'/'//trim(case_files(k))
    end do
  end function file_paths

  !> Remove a temporary case folder (it holds only files this program wrote).
  subroutine discard(folder)
    character(*), intent(in) :: folder
    integer :: status, k
    do k = 1, size(case_files)
      status = remove_file(folder//'/'//trim(case_files(k)))
    end do
    status = remove_directory(folder)
    if (directory_exists(folder)) call remove_tree(folder)
  end subroutine discard

  !> Check the output root before any deck runs: a name is given, every
  !> existing part of the path is a folder, and a folder can be made in it (a
  !> probe folder is created and removed; a missing root is not created here,
  !> so a run whose decks all fail leaves nothing). Then remove what dead runs left in it.
  subroutine prepare_output_root(out_root, error)
    character(*), intent(in) :: out_root
    type(error_t), allocatable, intent(out) :: error
    character(:), allocatable :: probe, reason
    integer :: i
    if (len_trim(out_root) == 0) then
      call set_error(error, 'the output folder name is empty (-o ""): give a folder, e.g. -o out')
      return
    end if
    ! The first part of the path that does not exist (or the root itself, plus a probe name).
    probe = ''
    do i = 1, len(out_root)
      if (i < len(out_root) .and. out_root(i:i) /= '/') cycle
      if (i < len(out_root)) then
        if (out_root(i + 1:i + 1) == '/') cycle
      end if
      if (out_root(i:i) == '/' .and. i == 1) cycle
      associate (part => out_root(1:merge(i - 1, i, out_root(i:i) == '/')))
      if (.not. path_exists(part)) then
        probe = part
        exit
      end if
      if (.not. directory_exists(part)) then
        call set_error(error, 'cannot write into the output folder "'//out_root//'": '//part//' is not a folder')
        return
      end if
      end associate
    end do
    reason = 'cannot be created'
    if (len(probe) == 0) then
      probe = out_root//'/.visco2d-probe.'//integer_text(process_id())
      reason = 'is not writable'
    end if
    if (make_directory(probe) /= 0 .or. .not. directory_exists(probe)) then
      call set_error(error, 'the output folder "'//out_root//'" '//reason//' (no folder can be made at '// &
                     probe//'); give a writable folder with -o DIR')
      return
    end if
    if (remove_directory(probe) /= 0) continue
    if (directory_exists(out_root)) call remove_stale_folders(out_root)
  end subroutine prepare_output_root

  !> `<host>.<pid>` of this process: the end of the names of its temporary folders.
  function owner_tag() result(tag)
    character(:), allocatable :: tag
    tag = host_name()//'.'//integer_text(process_id())
  end function owner_tag

  !> Take the lock of case `case_name` in out_root (OUT/.<case>.lock; the root
  !> and its missing parents are made for it and removed again by unlock_case
  !> if they are then empty). The lock lasts until unlock_case or the end of
  !> the process, however it ends. If another run (of this host or another)
  !> holds it, an error naming that run: two runs of one case would overwrite
  !> each other's results.
  subroutine lock_case(out_root, case_name, lock, error)
    character(*), intent(in) :: out_root, case_name
    type(case_lock_t), intent(out) :: lock
    type(error_t), allocatable, intent(inout) :: error
    character(:), allocatable :: holder, parent, root
    integer :: status, slash, missing, k
    root = out_root
    do while (len(root) > 1 .and. root(len(root):) == '/')
      root = root(:len(root) - 1)
    end do
    missing = 0                                   ! the levels of the root that do not exist yet
    parent = root
    do while (len(parent) > 0 .and. .not. path_exists(parent))
      missing = missing + 1
      slash = index(parent, '/', back=.true.)
      if (slash <= 1) exit
      parent = parent(:slash - 1)
    end do
    allocate(lock%created(missing))               ! element by element: no array constructor of path_t
    parent = root
    do k = 1, missing
      lock%created(k)%path = parent
      slash = index(parent, '/', back=.true.)
      if (slash > 1) parent = parent(:slash - 1)
    end do
    if (make_directory(out_root) /= 0) then
      call set_error(error, 'cannot create the output folder '//out_root//'; nothing was written')
      return
    end if
    lock%path = out_root//'/.'//case_name//'.lock'
    call hold_interrupts(.true.)                  ! no interrupt between the take and the arm: the file would stay
    call lock_take(lock%path, 'process '//integer_text(process_id())//' on host '//host_name(), lock%fd, status, holder, &
                   patient=.true.)
    if (status == 0) call interrupt_lock_arm(lock%path)
    call hold_interrupts(.false.)
    if (status == 0) return
    lock%fd = -1
    if (status == 1) then
      if (len(holder) == 0) holder = 'a process that has not yet said which'
      call set_error(error, 'the case '//case_name//' is being run into '//out_root//' by another run ('// &
        holder//', which holds '//lock%path//'): two runs of one case would overwrite each other''s '// &
        out_root//'/'//case_name//'/; wait for that run to end, or give this one another -o folder')
    else
      call set_error(error, 'cannot lock '//lock%path//' ('//holder//'): the case is not run, so that no '// &
        'other run of it can overwrite its results unnoticed')
    end if
    call remove_created(lock)
  end subroutine lock_case

  !> Release the lock of a case (its file removed), and remove the folders
  !> lock_case made if they are empty (a deck that failed leaves nothing).
  subroutine unlock_case(lock)
    type(case_lock_t), intent(inout) :: lock
    if (lock%fd >= 0) then
      call hold_interrupts(.true.)                ! no interrupt between the disarm and the release
      call interrupt_lock_disarm()
      call lock_release(lock%fd, lock%path)
      call hold_interrupts(.false.)
      lock%fd = -1
    end if
    call remove_created(lock)
  end subroutine unlock_case

  !> Remove the folders lock_case made, deepest first, while they are empty.
  subroutine remove_created(lock)
    type(case_lock_t), intent(inout) :: lock
    integer :: k
    if (.not. allocated(lock%created)) return
    do k = 1, size(lock%created)
      if (remove_directory(lock%created(k)%path) /= 0) exit
    end do
    deallocate(lock%created)
    allocate(lock%created(0))
  end subroutine remove_created

  !> Remove what runs that no longer exist left in an output root: their
  !> temporary folders `.<case>.partial.<host>.<pid>` (a run stopped while
  !> writing), `.<case>.old.<host>.<pid>` (a previous case folder being
  !> replaced; it is put back as <case> when no <case> folder exists, else
  !> removed) and lock files `.<case>.lock` that nobody holds. A folder is
  !> left alone while the lock of its case is held (its run is alive, on any
  !> host and in any PID namespace), and a folder or lock file of another host
  !> is never removed (this host cannot see whether its process runs; a note
  !> says so); of this host, a folder of a live process is kept. Names
  !> without a host (`.<case>.partial.<pid>`, older versions) count as this
  !> host's. A note on stderr per folder removed or left.
  subroutine remove_stale_folders(out_root)
    character(*), intent(in) :: out_root
    type(path_t), allocatable :: paths(:)
    character(:), allocatable :: case_name, owner
    integer :: k
    logical :: stale
    paths = matching_paths(out_root, '.*.old.*')
    do k = 1, size(paths)
      call stale_owner(out_root, paths(k)%path, '.old.', case_name, owner, stale)
      if (.not. stale) cycle
      if (.not. directory_exists(out_root//'/'//case_name)) then
        if (rename_path(paths(k)%path, out_root//'/'//case_name) == 0) then
          write(0, '(a)') 'visco2d: note: put back '//out_root//'/'//case_name//' from '//paths(k)%path// &
            ' (left by '//owner//', which no longer runs)'
          cycle
        end if
      end if
      call remove_tree(paths(k)%path)
      write(0, '(a)') 'visco2d: note: removed '//paths(k)%path//' (left by '//owner//', which no longer runs)'
    end do
    paths = matching_paths(out_root, '.*.partial.*')
    do k = 1, size(paths)
      call stale_owner(out_root, paths(k)%path, '.partial.', case_name, owner, stale)
      if (.not. stale) cycle
      call remove_tree(paths(k)%path)
      write(0, '(a)') 'visco2d: note: removed the unfinished '//paths(k)%path//' (left by '//owner// &
        ', which no longer runs)'
    end do
    paths = matching_paths(out_root, '.?*.lock')
    do k = 1, size(paths)
      if (directory_exists(paths(k)%path)) cycle
      if (lock_free(paths(k)%path)) continue               ! a lock file nobody holds, of this host: removed
    end do
  end subroutine remove_stale_folders

  !> True if nobody holds the lock file `path` (a missing one included). A
  !> free lock file of this host (or naming none) is removed; one that names
  !> another host stays, as that host's run left it.
  logical function lock_free(path) result(free)
    character(*), intent(in) :: path
    character(:), allocatable :: holder
    integer :: fd, status, mark
    call lock_take(path, '', fd, status, holder, patient=.false.)
    free = status == 0
    if (.not. free) return
    mark = index(holder, ' on host ')
    if (mark > 0) then
      if (holder(mark + len(' on host '):) /= host_name()) then
        call lock_close(fd)
        return
      end if
    end if
    call lock_release(fd, path)
  end function lock_free

  !> Who left a `.<case><tag><host>.<pid>` (or `.<case><tag><pid>`) folder,
  !> "process <pid> on host <host>", and whether it is stale: a folder, the
  !> name well formed, the case's lock not held, of this host, and its
  !> process not alive (nor this one). A folder of another host whose case
  !> lock is free is left with a note.
  subroutine stale_owner(out_root, path, tag, case_name, owner, stale)
    character(*), intent(in) :: out_root, path, tag
    character(:), allocatable, intent(out) :: case_name, owner
    logical, intent(out) :: stale
    integer :: slash, status, mark, dot, pid
    character(:), allocatable :: name, digits, host, tail
    stale = .false.
    case_name = ''
    owner = ''
    slash = index(path, '/', back=.true.)
    name = path(slash + 1:)
    mark = index(name, tag, back=.true.)
    if (mark < 3) return
    case_name = name(2:mark - 1)
    tail = name(mark + len(tag):)
    dot = index(tail, '.', back=.true.)
    if (dot == 0) then
      host = host_name()
      digits = tail
    else
      host = tail(:dot - 1)
      digits = tail(dot + 1:)
    end if
    if (len(host) == 0 .or. len(digits) < 1 .or. len(digits) > 9 .or. verify(digits, '0123456789') /= 0) return
    read(digits, *, iostat=status) pid
    if (status /= 0 .or. pid <= 0) return
    if (.not. directory_exists(path)) return
    owner = 'process '//integer_text(pid)//' on host '//host
    if (.not. lock_free(out_root//'/.'//case_name//'.lock')) return   ! held (or cannot be told): alive
    if (host /= host_name()) then
      write(0, '(a)') 'visco2d: note: left '//path//' alone: written by '//owner//', another host, whose '// &
        'run this host cannot see; remove it by hand once that run has ended'
      return
    end if
    if (pid == process_id() .or. process_alive(pid)) return
    stale = .true.
  end subroutine stale_owner

end module visco2d_case_folder
