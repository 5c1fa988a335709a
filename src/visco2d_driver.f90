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
  use visco2d_contact, only: solve_static_contact
  use visco2d_record, only: record_t, record_put, record_put_integer, record_put_real
  use visco2d_output, only: write_summary, write_history, write_listing, write_results_h5
  use visco2d_timers, only: timers_enabled, timers_reset, timer_start, timer_stop, timers_report, phase_output
  use visco2d_system, only: make_directory, rename_path, remove_file, remove_directory, process_id, &
                            directory_exists, remove_tree
  use visco2d_estimate, only: run_size_t, estimate_run, check_run_size, print_estimate, size_before_work
  implicit none
  private

  public :: run_deck, check_deck, case_name_of, run_line, summary_value

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
    type(run_size_t) :: estimate
    call read_deck(path, deck, error)
    if (allocated(error)) return
    estimate = estimate_run(deck)                          ! size before work: over the memory limit, an error
    call check_run_size(deck, estimate, error)
    if (allocated(error)) return
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
  subroutine run_deck(path, out_root, record, error)
    character(*), intent(in) :: path, out_root
    type(record_t), intent(out) :: record
    type(error_t), allocatable, intent(out) :: error
    type(deck_t) :: deck
    type(effects_t) :: effects
    type(static_solution_t) :: static_solution
    character(:), allocatable :: case_name, final_dir, temporary_dir, old_dir
    real :: cpu_start, cpu_end
    integer(int64) :: clock_start, clock_end, clock_rate

    call cpu_time(cpu_start)
    call system_clock(clock_start, clock_rate)
    call timers_reset()
    case_name = case_name_of(path)
    call read_deck(path, deck, error)
    if (allocated(error)) return
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
      end if
      call progress_end()
      if (allocated(error)) return
    case default
      call set_error(error, 'no analysis to run', file=path)
      return
    end select
    call check_expectations(deck, record, error)
    if (allocated(error)) return
    call record_put_integer(record, 'warnings', size(deck%warnings))
    call cpu_time(cpu_end)
    call record_put(record, 'cpu_s', rtoa(real(cpu_end - cpu_start, dp)))

    ! Write everything under a temporary name, then move it into place.
    final_dir = out_root//'/'//case_name
    temporary_dir = out_root//'/.'//case_name//'.partial.'//itoa(process_id())
    old_dir = out_root//'/.'//case_name//'.old.'//itoa(process_id())
    if (make_directory(temporary_dir) /= 0) then
      call set_error(error, 'cannot create output folder '//temporary_dir, file=path)
      return
    end if
    call timer_start(phase_output)
    call write_all(error)
    call timer_stop(phase_output)
    if (allocated(error)) then
      call discard(temporary_dir)
      return
    end if
    if (directory_exists(final_dir)) then
      if (rename_path(final_dir, old_dir) /= 0) then
        call discard(temporary_dir)
        call set_error(error, 'cannot replace the existing output folder '//final_dir, file=path)
        return
      end if
    end if
    if (rename_path(temporary_dir, final_dir) /= 0) then
      call discard(temporary_dir)
      call set_error(error, 'cannot create output folder '//final_dir, file=path)
      return
    end if
    if (directory_exists(old_dir)) call remove_tree(old_dir)
    if (timers_enabled()) then
      call system_clock(clock_end)
      call timers_report(6, case_name//' ('//itoa(2*deck%mesh%nnode)//' equations, half-bandwidth '// &
        itoa(deck%mesh%half_bandwidth)//')', real(clock_end - clock_start, dp)/real(clock_rate, dp))
    end if

  contains

    subroutine write_all(error)
      type(error_t), allocatable, intent(inout) :: error
      integer :: status
      call write_summary(temporary_dir//'/summary.txt', record, status)
      if (status /= 0) then
        call set_error(error, 'cannot write summary.txt in '//temporary_dir, file=path); return
      end if
      call write_history(temporary_dir//'/history.csv', record, status)
      if (status /= 0) then
        call set_error(error, 'cannot write history.csv in '//temporary_dir, file=path); return
      end if
      call write_listing(temporary_dir//'/listing.txt', case_name, deck, effects_text(effects), record, status)
      if (status /= 0) then
        call set_error(error, 'cannot write listing.txt in '//temporary_dir, file=path); return
      end if
      call write_results_h5(temporary_dir//'/results.h5', case_name, deck, record, status)
      if (status /= 0) then
        call set_error(error, 'cannot write results.h5 in '//temporary_dir//' (HDF5 status '// &
                       itoa(status)//')', file=path); return
      end if
    end subroutine write_all
  end subroutine run_deck

  !> Print the deck's warnings on stderr (`visco2d: warning: file:line: CARD: text`).
  subroutine print_warnings(deck)
    type(deck_t), intent(in) :: deck
    integer :: k
    do k = 1, size(deck%warnings)
      write(0, '(a)') 'visco2d: warning: '//deck%warnings(k)%text
    end do
  end subroutine print_warnings

  !> Remove a temporary case folder (it holds only files this program wrote).
  subroutine discard(folder)
    character(*), intent(in) :: folder
    integer :: status
    status = remove_file(folder//'/summary.txt')
    status = remove_file(folder//'/history.csv')
    status = remove_file(folder//'/listing.txt')
    status = remove_file(folder//'/results.h5')
    status = remove_directory(folder)
  end subroutine discard

  !> Compare the EXPECT cards with the summary; record the relative errors.
  subroutine check_expectations(deck, record, error)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    type(error_t), allocatable, intent(inout) :: error
    integer :: k, i, ios
    real(dp) :: computed, relative
    logical :: found
    do k = 1, size(deck%expects)
      found = .false.
      do i = 1, record%nsummary
        if (to_upper(trim(record%summary(i)%key)) /= deck%expects(k)%key) cycle
        read(record%summary(i)%value, *, iostat=ios) computed
        if (ios /= 0) exit
        found = .true.
        relative = abs(computed - deck%expects(k)%value)/max(abs(deck%expects(k)%value), tiny(1.0_dp))
        call record_put_real(record, 'expect_'//trim(record%summary(i)%key)//'_value', deck%expects(k)%value)
        call record_put_real(record, 'expect_'//trim(record%summary(i)%key)//'_rel_error', relative)
        call record_put(record, 'expect_'//trim(record%summary(i)%key)//'_within_rtol', &
                        trim(merge('yes', 'no ', relative <= deck%expects(k)%tolerance)))
        exit
      end do
      if (.not. found) then
        call set_error(error, 'key "'//to_lower(deck%expects(k)%key)//'" is not a numeric summary key '// &
          'of this run (see summary.txt for the keys)', file=deck%cards%file, line=deck%expects(k)%line, card='EXPECT')
        return
      end if
    end do
  end subroutine check_expectations

  !> The one-line report printed for a deck by the command line program:
  !> case, mesh size, the main result, the EXPECT checks and the CPU time.
  function run_line(record) result(line)
    type(record_t), intent(in) :: record
    character(:), allocatable :: line
    character(:), allocatable :: key
    character(len=16) :: buffer
    integer :: i, checks, within, ios
    real(dp) :: worst, relative
    line = ''
    checks = 0
    within = 0
    worst = 0.0_dp
    do i = 1, record%nsummary
      key = trim(record%summary(i)%key)
      if (index(key, 'expect_') == 1 .and. index(key, '_rel_error') > 0) then
        checks = checks + 1
        read(record%summary(i)%value, *, iostat=ios) relative
        if (ios == 0) worst = max(worst, relative)
      end if
      if (index(key, 'expect_') == 1 .and. index(key, '_within_rtol') > 0) then
        if (record%summary(i)%value == 'yes') within = within + 1
      end if
    end do
    line = summary_value(record, 'case')//': '//summary_value(record, 'nodes')//' nodes, '// &
      summary_value(record, 'elements')//' elements, half-bandwidth '//summary_value(record, 'half_bandwidth')
    if (len(summary_value(record, 'max_displacement_m')) > 0) &
      line = line//'; max |u| = '//summary_value(record, 'max_displacement_m')//' m'
    if (checks > 0) then
      write(buffer, '(es9.2)') worst
      line = line//'; EXPECT '//itoa(within)//'/'//itoa(checks)//' within RTOL (worst rel. error '// &
             trim(adjustl(buffer))//')'
    end if
    line = line//'; cpu '//summary_value(record, 'cpu_s')//' s'
  end function run_line

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
