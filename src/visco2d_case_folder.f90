!> The case folders of a run: the output root checked (and cleared of what
!> dead runs left) before any deck runs, and the files of one case written
!> under a temporary name and renamed into place only when every file is
!> complete, so a failed deck never leaves half-written output.
module visco2d_case_folder
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: itoa
  use visco2d_deck, only: deck_t
  use visco2d_record, only: record_t
  use visco2d_output, only: write_summary, write_history, write_results_h5, write_pressure
  use visco2d_listing, only: write_listing
  use visco2d_xdmf, only: write_results_xdmf
  use visco2d_system, only: make_directory, rename_path, remove_file, remove_directory, process_id, &
                            directory_exists, path_exists, remove_tree, process_alive, matching_paths, path_t, &
                            interrupt_cleanup_arm, interrupt_cleanup_restore, interrupt_cleanup_disarm
  implicit none
  private

  public :: write_case_folder, prepare_output_root, remove_stale_folders

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
    character(:), allocatable :: final_dir, temporary_dir, old_dir, message, file
    logical :: replaced

    final_dir = out_root//'/'//case_name
    temporary_dir = out_root//'/.'//case_name//'.partial.'//itoa(process_id())
    old_dir = out_root//'/.'//case_name//'.old.'//itoa(process_id())
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
      call write_summary(temporary_dir//'/'//file, record, message)
      if (len(message) == 0) then
        file = 'history.csv'
        call write_history(temporary_dir//'/'//file, record, message)
      end if
      if (len(message) == 0) then
        file = 'listing.txt'
        call write_listing(temporary_dir//'/'//file, case_name, deck, effects, record, message)
      end if
      if (len(message) == 0) then
        file = 'results.h5'
        call write_results_h5(temporary_dir//'/'//file, case_name, deck, record, message)
      end if
      if (len(message) == 0 .and. allocated(record%pressure%columns)) then
        file = 'pressure.csv'
        call write_pressure(temporary_dir//'/'//file, record, message)
      end if
      if (len(message) == 0) then
        file = 'results.xmf'
        call write_results_xdmf(temporary_dir//'/'//file, deck, record, message)
      end if
      if (len(message) > 0) then
        call discard(temporary_dir)
        call set_error(error, 'cannot write '//final_dir//'/'//file//': '//message//'; no output was kept', file=path)
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
      probe = out_root//'/.visco2d-probe.'//itoa(process_id())
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

  !> Remove what runs that no longer exist left in an output root: their
  !> temporary folders `.<case>.partial.<pid>` (a run stopped while writing)
  !> and `.<case>.old.<pid>` (a previous case folder being replaced; it is
  !> put back as <case> when no <case> folder exists, else removed). Folders of
  !> a process that is alive (this one included) are left alone. A note on stderr per folder.
  subroutine remove_stale_folders(out_root)
    character(*), intent(in) :: out_root
    type(path_t), allocatable :: paths(:)
    character(:), allocatable :: name, case_name
    integer :: k, pid, mark
    paths = matching_paths(out_root, '.*.old.*')
    do k = 1, size(paths)
      call stale_pid(paths(k)%path, '.old.', pid, mark)
      if (pid <= 0) cycle
      name = paths(k)%path(index(paths(k)%path, '/', back=.true.) + 1:)
      case_name = name(2:mark - 1)
      if (len(case_name) == 0) cycle
      if (.not. directory_exists(out_root//'/'//case_name)) then
        if (rename_path(paths(k)%path, out_root//'/'//case_name) == 0) then
          write(0, '(a)') 'visco2d: note: put back '//out_root//'/'//case_name//' from '//paths(k)%path// &
            ' (left by process '//itoa(pid)//', which no longer runs)'
          cycle
        end if
      end if
      call remove_tree(paths(k)%path)
      write(0, '(a)') 'visco2d: note: removed '//paths(k)%path//' (left by process '//itoa(pid)// &
        ', which no longer runs)'
    end do
    paths = matching_paths(out_root, '.*.partial.*')
    do k = 1, size(paths)
      call stale_pid(paths(k)%path, '.partial.', pid, mark)
      if (pid <= 0) cycle
      call remove_tree(paths(k)%path)
      write(0, '(a)') 'visco2d: note: removed the unfinished '//paths(k)%path//' (left by process '// &
        itoa(pid)//', which no longer runs)'
    end do
  end subroutine remove_stale_folders

  !> The pid of a stale `<...><tag><pid>` folder (0 if the name does not end
  !> so, if it is not a folder, or if the process is alive) and where the tag starts in the name.
  subroutine stale_pid(path, tag, pid, mark)
    character(*), intent(in) :: path, tag
    integer, intent(out) :: pid, mark
    integer :: slash, status
    character(:), allocatable :: name, digits
    pid = 0
    slash = index(path, '/', back=.true.)
    name = path(slash + 1:)
    mark = index(name, tag, back=.true.)
    if (mark < 2) return
    digits = name(mark + len(tag):)
    if (len(digits) < 1 .or. len(digits) > 9 .or. verify(digits, '0123456789') /= 0) return
    read(digits, *, iostat=status) pid
    if (status /= 0) pid = 0
    if (pid <= 0) return
    if (pid == process_id() .or. process_alive(pid) .or. .not. directory_exists(path)) pid = 0
  end subroutine stale_pid

end module visco2d_case_folder
