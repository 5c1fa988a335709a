!> Progress of a long run on stderr: after `delay` seconds of wall time
!> (2 s by default, so short runs stay silent) a line
!>
!>   visco2d: <label>: step N, t = X ms, alpha = Y mm, ~Z s left
!>
!> at most 4 times a second. On a terminal the line is overwritten in place
!> (carriage return) and ends with a newline at progress_end; when forced on
!> and not on a terminal (a log file, a pipe), each update is a whole line,
!> at most one a second. progress_end writes a last line "..., done in W s"
!> if anything was shown. Modes: auto (the default: shown only when stderr
!> is a terminal, so batch runs into files stay quiet), on, off.
!>
!> The time left is the rate of the steps so far, extrapolated linearly:
!> (wall time since the first step) x (t_end - t)/(t - t at the first step),
!> so the set-up (assembly, first factorization) does not inflate it. A run
!> that a STOP criterion ends before t_end finishes sooner than estimated.
!>
!> The state is module-level, as visco2d_timers' is: the solver calls
!> progress_step from its time loop without threading a handle through.
!> When off (or not yet due) progress_step returns at once or after one
!> system_clock call; it never allocates.
module visco2d_progress
  use, intrinsic :: iso_fortran_env, only: int64, error_unit
  use, intrinsic :: iso_c_binding, only: c_int
  use visco2d_kinds, only: dp, hertz_time_constant
  implicit none
  private

  public :: progress_auto, progress_on, progress_off
  public :: progress_configure, progress_begin, progress_step, progress_end
  public :: progress_expect_end, progress_impact_end
  public :: progress_enabled, progress_estimate, progress_format

  integer, parameter :: progress_auto = 0  !< shown when stderr is a terminal
  integer, parameter :: progress_on = 1    !< always shown
  integer, parameter :: progress_off = 2   !< never shown

  real(dp), parameter :: default_delay = 2.0_dp      !< s of wall time before the first line
  real(dp), parameter :: terminal_interval = 0.25_dp !< s between updates on a terminal
  real(dp), parameter :: log_interval = 1.0_dp       !< s between whole lines (logs stay readable)
  real(dp), parameter :: left_cap = 1.0e6_dp         !< s; longer estimates print as "?"
  integer, parameter :: line_length = 200

  interface
    !> POSIX isatty(3): 1 if the descriptor is a terminal.
    function c_isatty(descriptor) bind(c, name='isatty') result(answer)
      import :: c_int
      integer(c_int), value :: descriptor
      integer(c_int) :: answer
    end function c_isatty
  end interface

  logical, save :: enabled = .false.      !< the mode and the unit allow output
  logical, save :: terminal = .false.     !< overwrite the line in place
  integer, save :: out_unit = error_unit
  real(dp), save :: delay_seconds = default_delay

  logical, save :: running = .false.      !< between progress_begin and progress_end
  logical, save :: shown = .false.        !< something was written for this run
  integer, save :: last_length = 0        !< length of the last line written (to blank its tail)
  integer(int64), save :: rate = 1, start = 0, next_update = 0, interval_ticks = 1
  integer(int64), save :: anchor = 0      !< clock at the first step (the estimate leaves out the set-up)
  logical, save :: anchored = .false.
  real(dp), save :: anchor_time = 0.0_dp  !< the run's time at the first step
  real(dp), save :: end_time = 0.0_dp, deck_end_time = 0.0_dp
  integer, save :: last_step = 0
  real(dp), save :: last_t = 0.0_dp, last_alpha = -1.0_dp
  character(len=64), save :: run_name = ''

contains

  !> Set the mode (progress_auto, progress_on or progress_off), the delay
  !> before the first line (s, default 2) and, for tests, the output unit
  !> (default stderr). With a unit other than stderr, auto means off (it is
  !> not a terminal one can see) and lines are whole lines.
  subroutine progress_configure(mode, delay, unit)
    integer, intent(in) :: mode
    real(dp), intent(in), optional :: delay
    integer, intent(in), optional :: unit
    logical :: stderr_terminal
    out_unit = error_unit
    if (present(unit)) out_unit = unit
    delay_seconds = default_delay
    if (present(delay)) delay_seconds = max(0.0_dp, delay)
    stderr_terminal = .false.
    if (out_unit == error_unit) stderr_terminal = c_isatty(2_c_int) == 1_c_int
    select case (mode)
    case (progress_on)
      enabled = .true.
    case (progress_off)
      enabled = .false.
    case default
      enabled = stderr_terminal
    end select
    terminal = enabled .and. stderr_terminal
    running = .false.
    shown = .false.
  end subroutine progress_configure

  !> Whether progress_step may write anything (the mode and the unit).
  logical function progress_enabled()
    progress_enabled = enabled
  end function progress_enabled

  !> A run starts (the delay counts from here, set-up included): `label`
  !> names it (the case), `t_end` is the time the run is expected to reach
  !> (s; for the estimate of the time left).
  subroutine progress_begin(label, t_end)
    character(*), intent(in) :: label
    real(dp), intent(in) :: t_end
    running = .false.
    shown = .false.
    if (.not. enabled) return
    run_name = label
    end_time = t_end
    deck_end_time = t_end
    last_step = 0
    last_t = 0.0_dp
    last_alpha = -1.0_dp
    last_length = 0
    anchored = .false.
    call system_clock(start, rate)
    if (rate <= 0) rate = 1
    next_update = start + nint(delay_seconds*real(rate, dp), int64)
    if (terminal) then
      interval_ticks = max(1_int64, nint(terminal_interval*real(rate, dp), int64))
    else
      interval_ticks = max(1_int64, nint(log_interval*real(rate, dp), int64))
    end if
    running = .true.
  end subroutine progress_begin

  !> After each step: `step` steps done, the run's time `t` (s), the
  !> approach `alpha_mm` (mm; < 0: not an impact or no contact yet, omitted).
  subroutine progress_step(step, t, alpha_mm)
    integer, intent(in) :: step
    real(dp), intent(in) :: t, alpha_mm
    integer(int64) :: now
    if (.not. running) return
    last_step = step
    last_t = t
    last_alpha = alpha_mm
    call system_clock(now)
    if (.not. anchored) then
      anchor = now
      anchor_time = t
      anchored = .true.
    end if
    if (now < next_update) return
    next_update = now + interval_ticks
    call show(now, .false.)
  end subroutine progress_step

  !> A better guess of the time the run will end (s), once the run knows
  !> more (an impact that STOP AT ends before TEND): later estimates use it.
  !> Never past the t_end of progress_begin; ignored unless > 0.
  subroutine progress_expect_end(t_end)
    real(dp), intent(in) :: t_end
    if (.not. running) return
    if (t_end > 0.0_dp) end_time = min(t_end, deck_end_time)
  end subroutine progress_expect_end

  !> The end of an impact from its state now, for progress_expect_end:
  !> Hertz's energy balance 1/2 M (V^2 - v^2) = 2/5 k alpha^(5/2) gives
  !> alpha_m = alpha (V^2/(V^2 - v^2))^(2/5) without the material or the
  !> shape, then t_m = 1.4716 alpha_m/V after first contact (eq. [44]);
  !> to separation, 2 t_m. t_contact: time of first contact (s), alpha:
  !> approach now (m), v and v_contact: centre-of-mass velocity now and at
  !> first contact (m/s, either sign). -1 when there is no estimate yet
  !> (no approach, or no speed lost). Exact for a Hertz contact; a
  !> viscoelastic body, gravity and waves make it a guess that improves as
  !> v -> 0 (level-4 Table 1 run, t_alpha_max 1.52 ms: 4 % high at 0.3 ms
  !> after contact, 1 % at 1.1 ms).
  pure real(dp) function progress_impact_end(t_contact, alpha, v, v_contact, to_separation) result(t_end)
    real(dp), intent(in) :: t_contact, alpha, v, v_contact
    logical, intent(in) :: to_separation
    real(dp) :: lost, alpha_max, t_max
    t_end = -1.0_dp
    lost = v_contact**2 - v**2
    if (.not. (alpha > 0.0_dp .and. lost > 0.0_dp .and. t_contact >= 0.0_dp)) return
    alpha_max = alpha*(v_contact**2/lost)**0.4_dp
    t_max = hertz_time_constant*alpha_max/abs(v_contact)
    if (to_separation) then
      t_end = t_contact + 2.0_dp*t_max
    else
      t_end = t_contact + t_max
    end if
  end function progress_impact_end

  !> The run is over: if anything was shown, a last line with the wall time
  !> ("done in W s") and a newline. Call it on errors too (before the
  !> message), so the message starts on a line of its own.
  subroutine progress_end()
    integer(int64) :: now
    if (.not. running) return
    running = .false.
    if (.not. shown) return
    call system_clock(now)
    call show(now, .true.)
  end subroutine progress_end

  !> Write the line for the last step (no allocation: fixed-length buffers).
  subroutine show(now, final)
    integer(int64), intent(in) :: now
    logical, intent(in) :: final
    character(len=line_length) :: line
    integer :: n, pad
    real(dp) :: elapsed
    if (final) then      ! the whole run
      elapsed = real(now - start, dp)/real(rate, dp)
      call progress_format(line, n, trim(run_name), last_step, last_t, last_alpha, elapsed, anchor_time, end_time, final)
    else                 ! the steps only: the rate since the first step
      elapsed = real(now - anchor, dp)/real(rate, dp)
      call progress_format(line, n, trim(run_name), last_step, last_t, last_alpha, elapsed, anchor_time, end_time, final)
    end if
    if (terminal) then
      pad = max(0, last_length - n)
      if (final) then
        write(out_unit, '(3a)') achar(13), line(1:n), repeat(' ', pad)
      else
        write(out_unit, '(3a)', advance='no') achar(13), line(1:n), repeat(' ', pad)
      end if
    else
      write(out_unit, '(a)') line(1:n)
    end if
    flush(out_unit)
    last_length = n
    shown = .true.
  end subroutine show

  !> Estimated seconds left: elapsed (t_end - t)/(t - t_begin); 0 from
  !> t_end on; -1 (unknown) when t has not advanced or the estimate exceeds
  !> the cap (10^6 s): the rate of the run so far, extrapolated linearly.
  pure real(dp) function progress_estimate(elapsed, t, t_begin, t_end) result(left)
    real(dp), intent(in) :: elapsed, t, t_begin, t_end
    if (t >= t_end) then
      left = 0.0_dp
      return
    end if
    left = -1.0_dp
    if (.not. (t > t_begin)) return
    left = elapsed*((t_end - t)/(t - t_begin))
    if (.not. (left <= left_cap)) left = -1.0_dp
  end function progress_estimate

  !> The progress line in `line(1:length)`:
  !>   visco2d: LABEL: step N, t = X ms, alpha = Y mm, ~Z s left
  !> (t in s from 1 s on; alpha omitted when < 0; "~? s left" when unknown;
  !> the estimate with one decimal below 10 s, else whole seconds); when `final`,
  !> "..., done in W s" instead of the estimate.
  pure subroutine progress_format(line, length, run_label, step, t, alpha_mm, elapsed, t_begin, t_end, final)
    character(len=*), intent(out) :: line
    integer, intent(out) :: length
    character(*), intent(in) :: run_label
    integer, intent(in) :: step
    real(dp), intent(in) :: t, alpha_mm, elapsed, t_begin, t_end
    logical, intent(in) :: final
    character(len=32) :: field
    real(dp) :: left
    line = ''
    length = 0
    call append(line, length, 'visco2d: ')
    call append(line, length, run_label)
    call append(line, length, ': step ')
    write(field, '(i0)') step
    call append(line, length, trim(field))
    call append(line, length, ', t = ')
    if (abs(t) < 1.0_dp) then
      call append(line, length, trim(decimal(1.0e3_dp*t, 4)))
      call append(line, length, ' ms')
    else                    ! quasi-static creep runs: seconds to hours
      call append(line, length, trim(decimal(t, 3)))
      call append(line, length, ' s')
    end if
    if (alpha_mm >= 0.0_dp) then
      call append(line, length, ', alpha = ')
      call append(line, length, trim(decimal(alpha_mm, 4)))
      call append(line, length, ' mm')
    end if
    if (final) then
      call append(line, length, ', done in ')
      call append(line, length, trim(decimal(elapsed, 1)))
      call append(line, length, ' s')
    else
      left = progress_estimate(elapsed, t, t_begin, t_end)
      if (left < 0.0_dp) then
        call append(line, length, ', ~? s left')
      else if (left < 10.0_dp) then
        call append(line, length, ', ~'//trim(decimal(left, 1))//' s left')
      else
        write(field, '(i0)') nint(left)
        call append(line, length, ', ~'//trim(field)//' s left')
      end if
    end if
  end subroutine progress_format

  !> Append text to line(1:length) (cut at the line's length).
  pure subroutine append(line, length, text)
    character(len=*), intent(inout) :: line
    integer, intent(inout) :: length
    character(*), intent(in) :: text
    integer :: n
    n = min(len(text), len(line) - length)
    if (n <= 0) return
    line(length + 1:length + n) = text(1:n)
    length = length + n
  end subroutine append

  !> A value with `digits` decimals and a leading zero (f0.d drops it).
  pure function decimal(value, digits) result(text)
    real(dp), intent(in) :: value
    integer, intent(in) :: digits
    character(len=24) :: text
    character(len=8) :: form
    write(form, '(a, i0, a)') '(f0.', digits, ')'
    if (.not. (abs(value) < 1.0e12_dp)) then      ! huge or NaN
      write(text, '(es11.3e3)') value
    else
      write(text, form) value
    end if
    text = adjustl(text)
    if (text(1:1) == '.') then
      text = '0'//text(1:len(text) - 1)
    else if (text(1:2) == '-.') then
      text = '-0'//text(2:)
    end if
  end function decimal
end module visco2d_progress
