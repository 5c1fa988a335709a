!> The run driver: deck -> scene -> analysis -> outputs. check_deck reads a
!> deck and prints what a run would do; run_deck reads, solves, checks the
!> results (finite values, EXPECT cards: visco2d_expect) and writes the case
!> folder (visco2d_case_folder).
module visco2d_driver
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp, kinematics_large
  use visco2d_error, only: error_t, set_error, locate_error
  use visco2d_strings, only: integer_text, message_real
  use visco2d_deck, only: deck_t, read_deck, analysis_static, analysis_quasistatic, analysis_dynamic, &
                          analysis_name, geometry_name, total_steps, formulation_name, initial_velocity, stop_name
  use visco2d_deck_types, only: solver_card_names
  use visco2d_scene, only: effects_t, scene_effects, effects_text
  use visco2d_pad_mesh, only: body_nodes, body_elements
  use visco2d_static, only: static_solution_t, solve_static, static_record
  use visco2d_plastic_static, only: plastic_summary_t, solve_plastic_static, plastic_record, any_plastic
  use visco2d_finite_static, only: finite_summary_t, finite_plate_t, solve_finite_static, finite_record
  use visco2d_contact, only: contact_t, contact_create
  use visco2d_quasistatic, only: solve_quasistatic
  use visco2d_plastic_quasistatic, only: solve_plastic_quasistatic
  use visco2d_dynamic, only: solve_dynamic
  use visco2d_progress, only: progress_begin, progress_end
  use visco2d_static_contact, only: solve_static_contact, solve_plastic_static_contact
  use visco2d_bruise, only: bruise_static
  use visco2d_record, only: record_t, record_put, record_put_integer, record_put_real, record_warn, record_real
  use visco2d_advice, only: time_scales_t, time_scales, time_step_warnings, energy_balance_warning
  use visco2d_output_check, only: check_finite_outputs
  use visco2d_timers, only: timers_enabled, timers_reset, timer_start, timer_stop, timers_report, phase_output
  use visco2d_estimate, only: run_size_t, estimate_run, check_run_size, check_run_time, print_estimate, size_before_work
  use visco2d_expect, only: expect_tally_t, check_expect_cards, check_expectations
  use visco2d_case_folder, only: write_case_folder, lock_case, unlock_case, case_lock_t
  implicit none
  private

  public :: run_deck, check_deck, case_name_of, run_warning_count

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
    if (deck%analysis /= analysis_static) print '(a)', '  time steps      '//integer_text(total_steps(deck))// &
      ' in '//integer_text(size(deck%stages))//' stage(s) to t = '//message_real(deck%stages(size(deck%stages))%end_time)//' s'
    if (deck%analysis == analysis_dynamic) then
      print '(a)', '  Wilson theta    '//message_real(deck%dynamics%theta)
      associate (velocity => initial_velocity(deck))
      print '(a)', '  initial v       ('//message_real(velocity(1))//', '//message_real(velocity(2))//') m/s'
      end associate
    end if
    if (deck%loads%gravity > 0.0_dp) print '(a)', '  gravity         '//message_real(deck%loads%gravity)//' m/s^2 in -z'
    if (deck%plate%line > 0) then
      print '(a)', '  plate           z = '//message_real(deck%plate%z)//' m, '// &
        trim(merge('STICK', 'SLIP ', deck%plate%stick))//', RELEASE='//trim(merge('YES', 'NO ', deck%plate%release))
      if (deck%analysis == analysis_dynamic) print '(a)', '  stop at         '//stop_name(deck%stop_at)
    end if
    if (deck%body%line > 0) print '(a)', '  second body     sphere R = '//message_real(deck%body%radius)//' m of '// &
      deck%body%material//', VZ = '//message_real(deck%body%velocity)//' m/s, '// &
      integer_text(deck%mesh%nnode - deck%pad%first_node + 1)//' nodes, '// &
      integer_text(deck%mesh%nelem - deck%pad%first_element + 1)//' elements'
    if (deck%pad%line > 0) print '(a)', '  pad             '//message_real(deck%pad%thickness)//' m of ' &
      //deck%pad%material// &
      ', top at z = '//message_real(deck%plate%z)//' m, '//integer_text(deck%mesh%nnode - deck%pad%first_node + 1)//' nodes, '// &
      integer_text(deck%mesh%nelem - deck%pad%first_element + 1)//' elements, bottom '// &
      trim(merge('BONDED', 'SLIP  ', deck%pad%bonded))
    scales = time_scales(deck)
    if (scales%contact_duration > 0.0_dp) print '(a)', '  contact time    '//message_real(scales%contact_duration)// &
      ' s (Hertz, eqs. [43]-[44]): '//message_real(scales%contact_duration/deck%stages(1)%dt)//' steps of the first DT'
    if (scales%pole_transit > 0.0_dp) print '(a)', '  pole transit    '//message_real(scales%pole_transit)// &
      ' s (wave transit of the pole element at c_p = '//message_real(scales%wave_speed)//' m/s): DT = '// &
      message_real(deck%stages(1)%dt/scales%pole_transit)//' transits'
    if (scales%body_transit > 0.0_dp) print '(a)', '  body transit    '//message_real(scales%body_transit)// &
      ' s (wave transit of the body): DT = '//message_real(deck%stages(1)%dt/scales%body_transit)//' transits'
    print '(a)', '  formulation     '//formulation_name(deck%settings%formulation)
    print '(a)', '  geometry        '//geometry_name(deck%settings%geometry)
    print '(a)', '  effects         '//effects_text(scene_effects(deck))
    print '(a)', '  materials       '//integer_text(size(deck%materials))
    print '(a)', '  nodes           '//integer_text(deck%mesh%nnode)
    print '(a)', '  elements        '//integer_text(deck%mesh%nelem)
    print '(a)', '  equations       '//integer_text(2*deck%mesh%nnode)
    print '(a)', '  half-bandwidth  '//integer_text(deck%mesh%half_bandwidth_before)//' as input, '// &
                 integer_text(deck%mesh%half_bandwidth)//' after reverse Cuthill-McKee'
    call print_estimate(estimate)
  end subroutine check_deck

  !> Run one deck into out_root/<case>/, holding the case's lock (lock_case:
  !> a second run of the same case into the same root, from this host or
  !> another, fails). `record` is returned for the caller's report.
  !> Every error names the deck file (the file alone where no line is known).
  subroutine run_deck(path, out_root, record, error, tally)
    character(*), intent(in) :: path, out_root
    type(record_t), intent(out) :: record
    type(error_t), allocatable, intent(out) :: error
    type(expect_tally_t), intent(out), optional :: tally    !< the EXPECT checks (for run_line)
    type(expect_tally_t) :: checks
    type(case_lock_t) :: lock
    call lock_case(out_root, case_name_of(path), lock, error)   ! held while the case runs: no other run of it
    if (.not. allocated(error)) then
      call run_deck_steps(path, out_root, record, checks, error)
      call unlock_case(lock)
    end if
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
    type(plastic_summary_t) :: plastic_summary
    type(finite_summary_t) :: finite_summary
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
    call record_put(record, 'geometry', geometry_name(deck%settings%geometry))
    call record_put(record, 'formulation', formulation_name(deck%settings%formulation))
    if (deck%solver_line > 0) call record_put(record, 'solver', trim(solver_card_names(deck%settings%solver)))
    call record_put(record, 'effects', effects_text(effects))
    call record_put_integer(record, 'nodes', deck%mesh%nnode)
    call record_put_integer(record, 'elements', deck%mesh%nelem)
    call record_put_integer(record, 'dofs', 2*deck%mesh%nnode)
    call record_put_integer(record, 'half_bandwidth_input', deck%mesh%half_bandwidth_before)
    call record_put_integer(record, 'half_bandwidth', deck%mesh%half_bandwidth)

    call solve(error)
    call print_run_warnings(record)
    if (allocated(error)) then
      call locate_error(error, deck%cards%file)     ! a failed solve found where the deck is not known
      return
    end if
    ! The results must be finite before anything is derived from them (EXPECT).
    call check_finite_outputs(deck, record, error)
    if (allocated(error)) return
    call check_expectations(deck, record, tally, error)
    if (allocated(error)) return
    call record_put_integer(record, 'warnings', size(deck%warnings) + run_warning_count(record))
    call put_warning_keys(deck, record)
    call cpu_time(cpu_end)
    call record_put_real(record, 'cpu_s', real(cpu_end - cpu_start, dp), digits=4)
    ! The last line of defence: nothing non-finite reaches listing.txt, summary.txt, history.csv, results.h5.
    call check_finite_outputs(deck, record, error)
    if (allocated(error)) return

    call timer_start(phase_output)
    call write_case_folder(path, out_root, case_name, deck, effects_text(effects), record, error)
    call timer_stop(phase_output)
    if (allocated(error)) return
    if (timers_enabled()) then
      call system_clock(clock_end)
      call timers_report(6, case_name//' ('//integer_text(2*deck%mesh%nnode)//' equations, half-bandwidth '// &
        integer_text(deck%mesh%half_bandwidth)//')', real(clock_end - clock_start, dp)/real(clock_rate, dp))
    end if

  contains

    !> After a dynamic run: the energy-balance warning (visco2d_advice), as a run-time warning.
    subroutine warn_energy_balance()
      real(dp) :: relative
      integer :: line
      logical :: found
      character(:), allocatable :: message
      call record_real(record, 'balance_error_max_rel', relative, found)
      if (.not. found) return
      call energy_balance_warning(deck, relative, message, line)
      if (len(message) > 0) call record_warn(record, message, file=deck%cards%file, line=line, card='TIME')
    end subroutine warn_energy_balance

    !> The analysis the deck asks for, into `record`.
    subroutine solve(error)
      type(error_t), allocatable, intent(inout) :: error
      select case (deck%analysis)
      case (analysis_static)
        call record_put_integer(record, 'steps', 1)
        if (deck%settings%kinematics == kinematics_large .and. deck%plate%line > 0) then   ! ... on the plate
          call solve_finite_static(deck%mesh, deck%materials, deck%settings, deck%loads, deck%source, &
                                   static_solution, finite_summary, error, finite_plate(deck))
          if (allocated(error)) return
          call static_record(deck%mesh, deck%settings, deck%probes, static_solution, record)
          call finite_record(finite_summary, record)
          call bruise_static(deck, static_solution%stress, static_solution%strain, record)
          call record_put_integer(record, 'factorizations', finite_summary%iterations)
        else if (deck%settings%kinematics == kinematics_large) then   ! finite deformation: increments and Newton
          call solve_finite_static(deck%mesh, deck%materials, deck%settings, deck%loads, deck%source, &
                                   static_solution, finite_summary, error)
          if (allocated(error)) return
          call static_record(deck%mesh, deck%settings, deck%probes, static_solution, record)
          call finite_record(finite_summary, record)
          call bruise_static(deck, static_solution%stress, static_solution%strain, record)
          call record_put_integer(record, 'factorizations', finite_summary%iterations)
        else if (effects%contact .and. any_plastic(deck%materials)) then   ! Newton with the plate as an active set
          call solve_plastic_static_contact(deck, record, error)
          if (allocated(error)) return
        else if (effects%contact) then
          call solve_static_contact(deck, record, error)
          if (allocated(error)) return
        else if (any_plastic(deck%materials)) then      ! load increments and Newton (visco2d_plastic_static)
          call solve_plastic_static(deck%mesh, deck%materials, deck%settings, deck%loads, deck%source, &
                                    static_solution, plastic_summary, error)
          if (allocated(error)) return
          call static_record(deck%mesh, deck%settings, deck%probes, static_solution, record)
          call plastic_record(deck%settings, plastic_summary, record)
          call bruise_static(deck, static_solution%stress, static_solution%strain, record)
          call record_put_integer(record, 'factorizations', plastic_summary%iterations)
        else
          call solve_static(deck%mesh, deck%materials, deck%settings, deck%loads, deck%source, static_solution, error)
          if (allocated(error)) return
          call static_record(deck%mesh, deck%settings, deck%probes, static_solution, record, body_nodes(deck), &
                             body_elements(deck))
          call bruise_static(deck, static_solution%stress, static_solution%strain, record)
          call record_put_integer(record, 'factorizations', 1)
        end if
      case (analysis_quasistatic, analysis_dynamic)                ! time stepping, with progress on stderr
        call record_put_integer(record, 'steps', total_steps(deck))
        call record_put_integer(record, 'time_stages', size(deck%stages))
        call record_put_real(record, 'dt_s', deck%stages(1)%dt)
        call progress_begin(case_name, deck%stages(size(deck%stages))%end_time)
        if (deck%analysis == analysis_quasistatic .and. any_plastic(deck%materials)) then   ! Newton in every step
          call solve_plastic_quasistatic(deck%mesh, deck%materials, deck%settings, deck%loads, deck%probes, &
            deck%stages, deck%source, record, error)
        else if (deck%analysis == analysis_quasistatic) then
          call solve_quasistatic(deck%mesh, deck%materials, deck%settings, deck%loads, deck%probes, deck%stages, &
            deck%source, record, error)
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

  !> The PLATE of a static KINEMATICS LARGE deck for visco2d_finite_static:
  !> its height, STICK or SLIP, the candidates and tolerance of visco2d_contact.
  function finite_plate(deck) result(plate)
    type(deck_t), intent(in) :: deck
    type(finite_plate_t) :: plate
    type(contact_t) :: contact
    call contact_create(deck, contact)
    plate%z = contact%z_plate
    plate%stick = contact%stick
    plate%candidates = contact%candidates
    plate%tolerance = contact%tolerance
  end function finite_plate

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
      call record_put(record, 'warning_'//integer_text(n), deck%warnings(k)%text)
    end do
    do k = 1, run_warning_count(record)
      n = n + 1
      call record_put(record, 'warning_'//integer_text(n), record%warnings(k)%text)
    end do
  end subroutine put_warning_keys

  !> Number of run-time warnings in a record (record_warn).
  pure integer function run_warning_count(record) result(count)
    type(record_t), intent(in) :: record
    count = 0
    if (allocated(record%warnings)) count = size(record%warnings)
  end function run_warning_count

end module visco2d_driver
