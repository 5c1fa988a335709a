!> Phase timers for `visco2d --timing` and `make bench`: wall-clock seconds
!> and call counts per phase of a run (assembly, factorization,
!> back-substitution, constitutive update, contact, output), plus the floor
!> the step loop is compared with: one back-substitution (forward and back
!> with the factor of visco2d_factor) of the same system. Off by default; when off, timer_start/timer_stop return at
!> once. The state is module-level on purpose, as a profiler's is: every
!> module reports into the same table without threading it through calls.
module visco2d_timers
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp
  implicit none
  private

  public :: timers_enable, timers_enabled, timers_reset, timer_start, timer_stop, timer_seconds, timer_calls
  public :: timers_set_floor, timers_floor, timers_set_steps, timers_steps, timers_report, timer_name
  public :: phase_assembly, phase_factorization, phase_solve, phase_constitutive, phase_contact, phase_output
  public :: phase_step_loop, phase_count

  integer, parameter :: phase_assembly = 1       !< element matrices, S~, loads (eq. [35])
  integer, parameter :: phase_factorization = 2  !< the factor of S~ (and the contact capacitance matrix)
  integer, parameter :: phase_solve = 3          !< back-substitutions (eq. [34])
  integer, parameter :: phase_constitutive = 4   !< strains, stresses, history, internal forces (eqs. [13]-[24])
  integer, parameter :: phase_contact = 5        !< contact search, adjusted displacements, pressure, impact measures
  integer, parameter :: phase_output = 6         !< history rows, snapshots, files
  integer, parameter :: phase_step_loop = 7      !< the whole time-step loop (contains 2-6)
  integer, parameter :: phase_count = 7

  character(len=20), parameter :: names(phase_count) = [character(len=20) :: 'assembly', 'factorization', &
    'back-substitution', 'constitutive update', 'contact', 'output', 'step loop']

  logical, save :: enabled = .false.
  integer(int64), save :: started(phase_count) = 0
  integer, save :: depth(phase_count) = 0       !< open timer_start calls of a phase (stages nest)
  integer(int64), save :: ticks(phase_count) = 0
  integer, save :: calls(phase_count) = 0
  real(dp), save :: floor_seconds = 0.0_dp
  integer, save :: step_total = 0

contains

  !> Switch the timers on or off (and clear them).
  subroutine timers_enable(on)
    logical, intent(in) :: on
    enabled = on
    call timers_reset()
  end subroutine timers_enable

  logical function timers_enabled()
    timers_enabled = enabled
  end function timers_enabled

  !> Clear every phase (at the start of a run).
  subroutine timers_reset()
    started = 0
    depth = 0
    ticks = 0
    calls = 0
    floor_seconds = 0.0_dp
    step_total = 0
  end subroutine timers_reset

  !> Start a phase's timer (each stage of the step times itself; a start
  !> inside an open one of the same phase is part of the outer one).
  subroutine timer_start(phase)
    integer, intent(in) :: phase
    if (.not. enabled) return
    depth(phase) = depth(phase) + 1
    if (depth(phase) == 1) call system_clock(started(phase))
  end subroutine timer_start

  !> Stop a phase's timer: a stage timed inside a stage of the same phase
  !> (trial_stresses in solve_point_state) is counted once, by the outer one.
  subroutine timer_stop(phase)
    integer, intent(in) :: phase
    integer(int64) :: now
    if (.not. enabled) return
    depth(phase) = depth(phase) - 1
    if (depth(phase) > 0) return
    depth(phase) = 0
    call system_clock(now)
    ticks(phase) = ticks(phase) + (now - started(phase))
    calls(phase) = calls(phase) + 1
  end subroutine timer_stop

  !> Wall-clock seconds spent in a phase since the last reset.
  real(dp) function timer_seconds(phase)
    integer, intent(in) :: phase
    integer(int64) :: rate
    call system_clock(count_rate=rate)
    timer_seconds = real(ticks(phase), dp)/real(rate, dp)
  end function timer_seconds

  integer function timer_calls(phase)
    integer, intent(in) :: phase
    timer_calls = calls(phase)
  end function timer_calls

  function timer_name(phase) result(name)
    integer, intent(in) :: phase
    character(:), allocatable :: name
    name = trim(names(phase))
  end function timer_name

  !> The floor: seconds of one back-substitution of the run's system.
  subroutine timers_set_floor(seconds)
    real(dp), intent(in) :: seconds
    floor_seconds = seconds
  end subroutine timers_set_floor

  real(dp) function timers_floor()
    timers_floor = floor_seconds
  end function timers_floor

  !> Number of time steps of the run (for the time per step).
  subroutine timers_set_steps(steps)
    integer, intent(in) :: steps
    step_total = steps
  end subroutine timers_set_steps

  integer function timers_steps()
    timers_steps = step_total
  end function timers_steps

  !> The phase table on `unit`: seconds, calls, share of the total, and the
  !> time per step against the floor.
  subroutine timers_report(unit, label, total_seconds)
    integer, intent(in) :: unit
    character(*), intent(in) :: label
    real(dp), intent(in) :: total_seconds
    integer :: phase
    real(dp) :: per_step
    write(unit, '(a)') 'timing: '//label
    write(unit, '(a)') 'timing:   phase                    seconds     calls   share'
    do phase = 1, phase_count
      write(unit, '(a, a20, f12.6, i10, f8.1, a)') 'timing:   ', names(phase), timer_seconds(phase), calls(phase), &
        100.0_dp*timer_seconds(phase)/max(total_seconds, tiny(1.0_dp)), ' %'
    end do
    write(unit, '(a, a20, f12.6)') 'timing:   ', 'whole run', total_seconds
    if (step_total > 0 .and. floor_seconds > 0.0_dp) then
      per_step = timer_seconds(phase_step_loop)/step_total
      write(unit, '(a, i0, a, es11.3e3, a, es11.3e3, a, f6.2)') 'timing:   steps ', step_total, &
        '  time per step ', per_step, ' s  floor (one solve) ', floor_seconds, ' s  ratio ', per_step/floor_seconds
    end if
  end subroutine timers_report
end module visco2d_timers
