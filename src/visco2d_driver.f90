!> The run driver: deck -> scene -> analysis -> outputs. A case folder is
!> written under a temporary name and renamed into place only when every
!> file is complete, so a failed deck never leaves half-written output.
module visco2d_driver
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, set_error, error_text
  use visco2d_strings, only: itoa, rtoa, to_upper, to_lower
  use visco2d_deck, only: deck_t, read_deck, analysis_static, analysis_quasistatic, analysis_dynamic, &
                          analysis_name, geometry_name, total_steps, formulation_name, initial_velocity, stop_name
  use visco2d_scene, only: effects_t, scene_effects, effects_text
  use visco2d_static, only: static_solution_t, solve_static, static_record, solve_quasistatic
  use visco2d_wilson, only: solve_dynamic
  use visco2d_progress, only: progress_begin, progress_end
  use visco2d_static_contact, only: solve_static_contact
  use visco2d_bruise, only: bruise_static
  use visco2d_record, only: record_t, record_put, record_put_integer, record_put_real, record_warn
  use visco2d_advice, only: time_scales_t, time_scales, time_step_warnings, energy_balance_warning
  use visco2d_output, only: write_summary, write_history, write_results_h5, write_pressure
  use visco2d_listing, only: write_listing
  use visco2d_xdmf, only: write_results_xdmf
  use visco2d_output_check, only: check_finite_outputs, finite_text
  use visco2d_timers, only: timers_enabled, timers_reset, timer_start, timer_stop, timers_report, phase_output
  use visco2d_system, only: make_directory, rename_path, remove_file, remove_directory, process_id, &
                            directory_exists, path_exists, remove_tree, process_alive, matching_paths, path_t, &
                            interrupt_cleanup_arm, interrupt_cleanup_restore, interrupt_cleanup_disarm
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use visco2d_estimate, only: run_size_t, estimate_run, check_run_size, check_run_time, print_estimate, size_before_work
  implicit none
  private

  public :: run_deck, check_deck, case_name_of, run_line, summary_value
  public :: prepare_output_root, remove_stale_folders, relative_error, run_warning_count
  public :: expect_tally_t

  !> The files of a case folder.
  character(len=*), parameter :: case_files(6) = [character(len=12) :: 'summary.txt', 'history.csv', &
                                                  'listing.txt', 'results.h5', 'results.xmf', 'pressure.csv']

  !> The EXPECT checks of a run: one per EXPECT card (the summary holds their
  !> expect_<key>_value, _rel_error and _within_rtol keys).
  type :: expect_tally_t
    integer :: count = 0          !< EXPECT cards checked
    integer :: within = 0         !< of them within their RTOL
    real(dp) :: worst = 0.0_dp    !< the largest relative error
  end type expect_tally_t

contains

  !> Case name of a deck path: its file name without folder and extension.
  pure function case_name_of(path) result(name)
    character(*), intent(in) :: path
    character(:), allocatable :: name
    integer :: slash, dot
    slash = index(path, '/', back=.true.)
    name = path(slash + 1:)
    dot = index(name, '.', back=.true.)
    if (dot > 1) name = name(1:dot - 1)
  end function case_name_of

  !> Parse and check a deck without solving; print mesh statistics and effects.
  subroutine check_deck(path, error)
    character(*), intent(in) :: path
    type(error_t), allocatable, intent(out) :: error
    type(deck_t) :: deck
    type(time_scales_t) :: scales
    type(run_size_t) :: estimate
    call read_deck(path, deck, error)
    if (.not. allocated(error)) call check_expect_cards(deck, error)
    if (allocated(error)) then
      call name_the_deck(error, path)
      return
    end if
    estimate = estimate_run(deck)                          ! size before work: over the memory limit, an error
    call check_run_size(deck, estimate, error)
    if (.not. allocated(error)) call check_run_time(deck, estimate, error)
    if (allocated(error)) return
    call time_step_warnings(deck)
    call print_warnings(deck)
    print '(a)', path//': ok'
    print '(a)', '  title           '//deck%title
    print '(a)', '  analysis        '//analysis_name(deck%analysis)
    if (deck%analysis /= analysis_static) print '(a)', '  time steps      '//itoa(total_steps(deck))// &
      ' in '//itoa(size(deck%stages))//' stage(s) to t = '//rtoa(deck%stages(size(deck%stages))%end_time)//' s'
    if (deck%analysis == analysis_dynamic) then
      print '(a)', '  Wilson theta    '//rtoa(deck%dynamics%theta)
      associate (velocity => initial_velocity(deck))
      print '(a)', '  initial v       ('//rtoa(velocity(1))//', '//rtoa(velocity(2))//') m/s'
      end associate
    end if
    if (deck%gravity > 0.0_dp) print '(a)', '  gravity         '//rtoa(deck%gravity)//' m/s^2 in -z'
    if (deck%plate%line > 0) then
      print '(a)', '  plate           z = '//rtoa(deck%plate%z)//' m, '// &
        trim(merge('STICK', 'SLIP ', deck%plate%stick))//', RELEASE='//trim(merge('YES', 'NO ', deck%plate%release))
      if (deck%analysis == analysis_dynamic) print '(a)', '  stop at         '//stop_name(deck%stop_at)
    end if
    scales = time_scales(deck)
    if (scales%contact_duration > 0.0_dp) print '(a)', '  contact time    '//rtoa(scales%contact_duration)// &
      ' s (Hertz, eqs. [43]-[44]): '//rtoa(scales%contact_duration/deck%stages(1)%dt)//' steps of the first DT'
    if (scales%pole_transit > 0.0_dp) print '(a)', '  pole transit    '//rtoa(scales%pole_transit)// &
      ' s (wave transit of the pole element at c_p = '//rtoa(scales%wave_speed)//' m/s): DT = '// &
      rtoa(deck%stages(1)%dt/scales%pole_transit)//' transits'
    if (scales%body_transit > 0.0_dp) print '(a)', '  body transit    '//rtoa(scales%body_transit)// &
      ' s (wave transit of the body): DT = '//rtoa(deck%stages(1)%dt/scales%body_transit)//' transits'
    print '(a)', '  formulation     '//formulation_name(deck%formulation)
    print '(a)', '  geometry        '//geometry_name(deck%geometry)
    print '(a)', '  effects         '//effects_text(scene_effects(deck))
    print '(a)', '  materials       '//itoa(size(deck%materials))
    print '(a)', '  nodes           '//itoa(deck%mesh%nnode)
    print '(a)', '  elements        '//itoa(deck%mesh%nelem)
    print '(a)', '  equations       '//itoa(2*deck%mesh%nnode)
    print '(a)', '  half-bandwidth  '//itoa(deck%mesh%half_bandwidth_before)//' as input, '// &
                 itoa(deck%mesh%half_bandwidth)//' after reverse Cuthill-McKee'
    call print_estimate(estimate)
  end subroutine check_deck

  !> Run one deck into out_root/<case>/. `record` is returned for the caller's report.
  !> Every error names the deck file (the file alone where no line is known).
  subroutine run_deck(path, out_root, record, error, tally)
    character(*), intent(in) :: path, out_root
    type(record_t), intent(out) :: record
    type(error_t), allocatable, intent(out) :: error
    type(expect_tally_t), intent(out), optional :: tally    !< the EXPECT checks (for run_line)
    type(expect_tally_t) :: checks
    call run_deck_steps(path, out_root, record, checks, error)
    if (allocated(error)) call name_the_deck(error, path)
    if (present(tally)) tally = checks
  end subroutine run_deck

  !> read, solve, check, write (run_deck).
  subroutine run_deck_steps(path, out_root, record, tally, error)
    character(*), intent(in) :: path, out_root
    type(record_t), intent(inout) :: record
    type(expect_tally_t), intent(inout) :: tally
    type(error_t), allocatable, intent(inout) :: error
    type(deck_t) :: deck
    type(effects_t) :: effects
    type(static_solution_t) :: static_solution
    character(:), allocatable :: case_name
    real :: cpu_start, cpu_end
    integer(int64) :: clock_start, clock_end, clock_rate

    call cpu_time(cpu_start)
    call system_clock(clock_start, clock_rate)
    call timers_reset()
    case_name = case_name_of(path)
    call read_deck(path, deck, error)
    if (allocated(error)) return
    call check_expect_cards(deck, error)
    if (allocated(error)) return
    call time_step_warnings(deck)
    call print_warnings(deck)
    call size_before_work(path, deck, error)    ! refused over the memory limit; a long run is announced
    if (allocated(error)) return
    effects = scene_effects(deck)

    call record_put(record, 'case', case_name)
    call record_put(record, 'title', deck%title)
    call record_put(record, 'analysis', analysis_name(deck%analysis))
    call record_put(record, 'geometry', geometry_name(deck%geometry))
    call record_put(record, 'formulation', formulation_name(deck%formulation))
    call record_put(record, 'effects', effects_text(effects))
    call record_put_integer(record, 'nodes', deck%mesh%nnode)
    call record_put_integer(record, 'elements', deck%mesh%nelem)
    call record_put_integer(record, 'dofs', 2*deck%mesh%nnode)
    call record_put_integer(record, 'half_bandwidth_input', deck%mesh%half_bandwidth_before)
    call record_put_integer(record, 'half_bandwidth', deck%mesh%half_bandwidth)

    call solve(error)
    call print_run_warnings(record)
    if (allocated(error)) return
    ! The results must be finite before anything is derived from them (EXPECT).
    call check_finite_outputs(deck, record, error)
    if (allocated(error)) return
    call check_expectations(deck, record, tally, error)
    if (allocated(error)) return
    call record_put_integer(record, 'warnings', size(deck%warnings) + run_warning_count(record))
    call put_warning_keys(deck, record)
    call cpu_time(cpu_end)
    call record_put(record, 'cpu_s', rtoa(real(cpu_end - cpu_start, dp)))
    ! The last line of defence: nothing non-finite reaches listing.txt, summary.txt, history.csv, results.h5.
    call check_finite_outputs(deck, record, error)
    if (allocated(error)) return

    call timer_start(phase_output)
    call write_case_folder(path, out_root, case_name, deck, effects_text(effects), record, error)
    call timer_stop(phase_output)
    if (allocated(error)) return
    if (timers_enabled()) then
      call system_clock(clock_end)
      call timers_report(6, case_name//' ('//itoa(2*deck%mesh%nnode)//' equations, half-bandwidth '// &
        itoa(deck%mesh%half_bandwidth)//')', real(clock_end - clock_start, dp)/real(clock_rate, dp))
    end if

  contains

    !> After a dynamic run: the energy-balance warning (visco2d_advice), as a run-time warning.
    subroutine warn_energy_balance()
      real(dp) :: relative
      integer :: ios, line
      character(:), allocatable :: text, message
      text = summary_value(record, 'balance_error_max_rel')
      read(text, *, iostat=ios) relative
      if (ios /= 0) return
      call energy_balance_warning(deck, relative, message, line)
      if (len(message) > 0) call record_warn(record, message, file=deck%cards%file, line=line, card='TIME')
    end subroutine warn_energy_balance

    !> The analysis the deck asks for, into `record`.
    subroutine solve(error)
      type(error_t), allocatable, intent(inout) :: error
      select case (deck%analysis)
      case (analysis_static)
        call record_put_integer(record, 'steps', 1)
        if (effects%contact) then
          call solve_static_contact(deck, record, error)
          if (allocated(error)) return
        else
          call solve_static(deck, static_solution, error)
          if (allocated(error)) return
          call static_record(deck, static_solution, record)
          call bruise_static(deck, static_solution%stress, static_solution%strain, record)
          call record_put_integer(record, 'factorizations', 1)
        end if
      case (analysis_quasistatic, analysis_dynamic)                ! time stepping, with progress on stderr
        call record_put_integer(record, 'steps', total_steps(deck))
        call record_put_integer(record, 'time_stages', size(deck%stages))
        call record_put_real(record, 'dt_s', deck%stages(1)%dt)
        call progress_begin(case_name, deck%stages(size(deck%stages))%end_time)
        if (deck%analysis == analysis_quasistatic) then
          call solve_quasistatic(deck, record, error)
        else
          call solve_dynamic(deck, record, error)
          if (.not. allocated(error)) call warn_energy_balance()
        end if
        call progress_end()
      case default
        call set_error(error, 'no analysis to run', file=path)
      end select
    end subroutine solve
  end subroutine run_deck_steps

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

  !> An error that names no file gets the deck's name.
  subroutine name_the_deck(error, path)
    type(error_t), intent(inout) :: error
    character(*), intent(in) :: path
    if (.not. allocated(error%file)) error%file = ''
    if (len(error%file) == 0) error%file = path
  end subroutine name_the_deck

  !> Print the deck's warnings on stderr (`visco2d: warning: file:line: CARD: text`).
  subroutine print_warnings(deck)
    type(deck_t), intent(in) :: deck
    integer :: k
    do k = 1, size(deck%warnings)
      write(0, '(a)') 'visco2d: warning: '//deck%warnings(k)%text
    end do
  end subroutine print_warnings

  !> Print the warnings the solver put in the record (record_warn), as the deck's are printed.
  subroutine print_run_warnings(record)
    type(record_t), intent(in) :: record
    integer :: k
    do k = 1, run_warning_count(record)
      write(0, '(a)') 'visco2d: warning: '//record%warnings(k)%text
    end do
  end subroutine print_run_warnings

  !> Each warning as a summary key, warning_1, warning_2, ... (the deck's,
  !> then the run's): a batch user reads them in summary.txt, not only on stderr.
  subroutine put_warning_keys(deck, record)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    integer :: k, n
    n = 0
    do k = 1, size(deck%warnings)
      n = n + 1
      call record_put(record, 'warning_'//itoa(n), deck%warnings(k)%text)
    end do
    do k = 1, run_warning_count(record)
      n = n + 1
      call record_put(record, 'warning_'//itoa(n), record%warnings(k)%text)
    end do
  end subroutine put_warning_keys

  !> Number of run-time warnings in a record (record_warn).
  pure integer function run_warning_count(record) result(count)
    type(record_t), intent(in) :: record
    count = 0
    if (allocated(record%warnings)) count = size(record%warnings)
  end function run_warning_count

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

  !> A second EXPECT card for the same key would overwrite the first's summary
  !> keys: refused before solving (an expected value of 0 or not finite is
  !> refused by the card reader).
  subroutine check_expect_cards(deck, error)
    type(deck_t), intent(in) :: deck
    type(error_t), allocatable, intent(inout) :: error
    integer :: k, j
    if (.not. allocated(deck%expects)) return
    do k = 1, size(deck%expects)
      associate (expect => deck%expects(k))
      do j = 1, k - 1
        if (deck%expects(j)%key /= expect%key) cycle
        call set_error(error, 'key '//to_lower(expect%key)//' is already expected on line '// &
          itoa(deck%expects(j)%line)//' (one EXPECT card per key)', file=deck%cards%file, line=expect%line, &
          column=positional_column(deck, expect%line, 1), card='EXPECT')
        return
      end do
      end associate
    end do
  end subroutine check_expect_cards

  !> Column of the n-th positional field of the card on a line (0 if unknown):
  !> on an EXPECT card, 1 is the key and 2 the value.
  integer function positional_column(deck, line, n) result(column)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: line, n
    integer :: i, t, positional
    column = 0
    if (.not. allocated(deck%cards%cards)) return
    do i = 1, min(deck%cards%count, size(deck%cards%cards))
      if (deck%cards%cards(i)%line /= line .or. .not. allocated(deck%cards%cards(i)%tokens)) cycle
      positional = 0
      do t = 1, size(deck%cards%cards(i)%tokens)
        if (.not. allocated(deck%cards%cards(i)%tokens(t)%name)) cycle
        if (len(deck%cards%cards(i)%tokens(t)%name) > 0) cycle
        positional = positional + 1
        if (positional == n) then
          column = deck%cards%cards(i)%tokens(t)%column
          return
        end if
      end do
    end do
  end function positional_column

  !> Compare the EXPECT cards with the summary; record per key the expected
  !> value, the relative error and whether it is within RTOL; count the checks in `tally`.
  subroutine check_expectations(deck, record, tally, error)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    type(expect_tally_t), intent(out) :: tally
    type(error_t), allocatable, intent(inout) :: error
    integer :: k, i, ios
    real(dp) :: computed, relative
    logical :: found
    do k = 1, size(deck%expects)
      found = .false.
      do i = 1, record%nsummary
        if (to_upper(trim(record%summary(i)%key)) /= deck%expects(k)%key) cycle
        if (.not. finite_text(record%summary(i)%value)) then
          call set_error(error, 'key "'//to_lower(deck%expects(k)%key)//'" is '//record%summary(i)%value// &
            ' in this run: it cannot be compared', file=deck%cards%file, line=deck%expects(k)%line, &
            column=positional_column(deck, deck%expects(k)%line, 1), card='EXPECT')
          return
        end if
        read(record%summary(i)%value, *, iostat=ios) computed
        if (ios /= 0) exit
        found = .true.
        relative = relative_error(computed, deck%expects(k)%value)
        tally%count = tally%count + 1
        tally%worst = max(tally%worst, relative)
        if (relative <= deck%expects(k)%tolerance) tally%within = tally%within + 1
        call record_put_real(record, 'expect_'//trim(record%summary(i)%key)//'_value', deck%expects(k)%value)
        call record_put_real(record, 'expect_'//trim(record%summary(i)%key)//'_rel_error', relative)
        call record_put(record, 'expect_'//trim(record%summary(i)%key)//'_within_rtol', &
                        trim(merge('yes', 'no ', relative <= deck%expects(k)%tolerance)))
        exit
      end do
      if (.not. found) then
        call set_error(error, 'key "'//to_lower(deck%expects(k)%key)//'" is not a numeric summary key '// &
          'of this run (see summary.txt for the keys)', file=deck%cards%file, line=deck%expects(k)%line, &
          column=deck%expects(k)%column, card='EXPECT')
        return
      end if
    end do
  end subroutine check_expectations

  !> |computed - expected| / |expected| for finite values and expected /= 0,
  !> without overflow: values beyond huge/4 are halved first (exact, so the
  !> result is that of the formula); a ratio above relative_error_ceiling
  !> (1e300: an expected value near the underflow limit) is reported as the
  !> ceiling, which no RTOL accepts.
  pure real(dp) function relative_error(computed, expected) result(relative)
    real(dp), intent(in) :: computed, expected
    real(dp), parameter :: relative_error_ceiling = 1.0e300_dp
    real(dp) :: scale, difference, reference
    relative = 0.0_dp
    if (computed == expected) return
    scale = 1.0_dp
    if (max(abs(computed), abs(expected)) > 0.25_dp*huge(1.0_dp)) scale = 0.5_dp
    difference = abs(scale*computed - scale*expected)
    reference = scale*abs(expected)
    if (difference >= reference*relative_error_ceiling) then
      relative = relative_error_ceiling
    else
      relative = difference/reference
    end if
  end function relative_error

  !> The one-line report printed for a deck by the command line program:
  !> case, mesh size, the main result, the EXPECT checks (one per EXPECT card,
  !> from run_deck's tally) and the CPU time.
  function run_line(record, tally) result(line)
    type(record_t), intent(in) :: record
    type(expect_tally_t), intent(in) :: tally
    character(:), allocatable :: line
    character(len=16) :: buffer
    line = summary_value(record, 'case')//': '//summary_value(record, 'nodes')//' nodes, '// &
      summary_value(record, 'elements')//' elements, half-bandwidth '//summary_value(record, 'half_bandwidth')
    if (len(summary_value(record, 'alpha_max_mm')) > 0) then          ! an impact: what a batch user looks for
      line = line//'; alpha_m = '//four_digits(summary_value(record, 'alpha_max_mm'))//' mm at '// &
        four_digits(summary_value(record, 't_alpha_max_ms'))//' ms, q_m = '// &
        four_digits(summary_value(record, 'q_max_MPa'))//' MPa'
      if (len(summary_value(record, 'bruise_volume_cm3')) > 0) &
        line = line//', bruise '//four_digits(summary_value(record, 'bruise_volume_cm3'))//' cm3'
    else if (len(summary_value(record, 'max_displacement_m')) > 0) then
      line = line//'; max |u| = '//summary_value(record, 'max_displacement_m')//' m'
    end if
    if (summary_value(record, 'warnings') /= '0' .and. len(summary_value(record, 'warnings')) > 0) &
      line = line//'; '//summary_value(record, 'warnings')//' warning(s)'
    if (tally%count > 0) then
      write(buffer, '(es10.2e3)') tally%worst
      line = line//'; EXPECT '//itoa(tally%within)//'/'//itoa(tally%count)//' within RTOL (worst rel. error '// &
             trim(adjustl(buffer))//')'
    end if
    line = line//'; cpu '//summary_value(record, 'cpu_s')//' s'
  end function run_line

  !> A summary number with four significant digits (the text as it is if it is not a number).
  function four_digits(text) result(short)
    character(*), intent(in) :: text
    character(:), allocatable :: short
    real(dp) :: value
    integer :: ios
    character(len=32) :: buffer
    short = text
    read(text, *, iostat=ios) value
    if (ios /= 0) return
    if (abs(value) >= 1.0e-3_dp .and. abs(value) < 1.0e5_dp .or. value == 0.0_dp) then
      write(buffer, '(g0.4)') value
    else
      write(buffer, '(es10.3e3)') value
    end if
    short = trim(adjustl(buffer))
  end function four_digits

  !> The text of a summary key ('' if absent).
  function summary_value(record, key) result(value)
    type(record_t), intent(in) :: record
    character(*), intent(in) :: key
    character(:), allocatable :: value
    integer :: i
    value = ''
    do i = 1, record%nsummary
      if (trim(record%summary(i)%key) == key) value = record%summary(i)%value
    end do
  end function summary_value
end module visco2d_driver
