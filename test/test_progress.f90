!> visco2d_progress: the line's text and the estimate of the time left
!> (exact, from the formula), then fake runs driven through the module with
!> the output directed to a scratch file: forced on with no delay (whole
!> lines, rate-limited, a last "done" line), a delay longer than the run (no
!> output at all), mode off, and auto on a unit that is not stderr (quiet).
!> Timing claims are checked only in the direction the clock guarantees
!> (a line appears only once the delay has passed; at most one line per
!> interval), never as CPU times. The cost of progress_step is printed, not
!> asserted.
program test_progress
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp
  use visco2d_progress, only: progress_auto, progress_on, progress_off, progress_configure, progress_begin, &
    progress_step, progress_end, progress_enabled, progress_estimate, progress_format, progress_expect_end, &
    progress_impact_end
  use visco2d_testing, only: check, check_close, test_summary
  use visco2d_strings, only: integer_text, message_real
  implicit none
  integer, parameter :: max_lines = 100
  character(len=200) :: line, lines(max_lines)
  integer :: n, count, scratch, k, first_shown, steps
  integer(int64) :: rate, before_begin, after_begin
  real(dp), allocatable :: before(:), after(:)
  real(dp) :: elapsed_run, cost_off, cost_idle
  real(dp) :: t_max_exact, alpha_max_exact, state(2), t_hertz, t_max_ode, t_sep_ode
  real(dp) :: at(3), alpha_at(3), v_at(3), t_end_at(3)

  call system_clock(count_rate=rate)

  ! ---------------------------------------------------------------- the text
  ! left = elapsed (t_end - t)/(t - t_begin) = 3 s x 4.5/1.5 = 9 s.
  call progress_format(line, n, 'case', 12, 1.5e-3_dp, 0.9643_dp, 3.0_dp, 0.0_dp, 6.0e-3_dp, .false.)
  call check('format_impact', line(1:n) == 'visco2d: case: step 12, t = 1.5000 ms, alpha = 0.9643 mm, ~9.0 s left', &
             '"'//line(1:n)//'"')
  call check('format_blank_after_length', line(n + 1:) == '', '"'//line//'"')
  ! alpha < 0: omitted; an estimate >= 10 s in whole seconds: 2 x (1 - 0.05)/0.05 = 38 s.
  call progress_format(line, n, 'creep', 7, 0.05_dp, -1.0_dp, 2.0_dp, 0.0_dp, 1.0_dp, .false.)
  call check('format_no_alpha', line(1:n) == 'visco2d: creep: step 7, t = 50.0000 ms, ~38 s left', '"'//line(1:n)//'"')
  ! t has not advanced: unknown.
  call progress_format(line, n, 'c', 0, 0.0_dp, -1.0_dp, 2.5_dp, 0.0_dp, 1.0_dp, .false.)
  call check('format_unknown_left', line(1:n) == 'visco2d: c: step 0, t = 0.0000 ms, ~? s left', '"'//line(1:n)//'"')
  ! Past the expected end: 0 left; from t = 1 s on, t in seconds (quasi-static creep runs).
  call progress_format(line, n, 'c', 5, 2.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, .false.)
  call check('format_past_end', line(1:n) == 'visco2d: c: step 5, t = 2.000 s, alpha = 0.0000 mm, ~0.0 s left', &
             '"'//line(1:n)//'"')
  call progress_format(line, n, 'creep', 74, 1.0e5_dp, -1.0_dp, 0.5_dp, 5.0e4_dp, 2.0e5_dp, .false.)
  call check('format_seconds', line(1:n) == 'visco2d: creep: step 74, t = 100000.000 s, ~1.0 s left', &
             '"'//line(1:n)//'"')
  ! The last line: the wall time instead of the estimate.
  call progress_format(line, n, 'case', 153, 1.52e-3_dp, 1.0371_dp, 4.76_dp, 0.0_dp, 4.0e-3_dp, .true.)
  call check('format_final', line(1:n) == 'visco2d: case: step 153, t = 1.5200 ms, alpha = 1.0371 mm, done in 4.8 s', &
             '"'//line(1:n)//'"')
  ! A long label is cut at the buffer, not an error.
  call progress_format(line(1:20), n, repeat('x', 50), 1, 0.0_dp, -1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, .false.)
  call check('format_cut_at_buffer', n == 20 .and. line(1:20) == 'visco2d: '//repeat('x', 11), '"'//line(1:20)//'"')

  ! ---------------------------------------------------------- the estimate
  call check_close('estimate_linear', progress_estimate(3.0_dp, 1.5e-3_dp, 0.0_dp, 6.0e-3_dp), 9.0_dp, 1.0e-14_dp)
  ! From t_begin = 1 s: 4 s x (3 - 2)/(2 - 1) = 4 s.
  call check_close('estimate_from_t_begin', progress_estimate(4.0_dp, 2.0_dp, 1.0_dp, 3.0_dp), 4.0_dp, 1.0e-14_dp)
  call check('estimate_not_advanced', progress_estimate(1.0_dp, 1.0_dp, 1.0_dp, 3.0_dp) < 0.0_dp)
  call check('estimate_past_end', progress_estimate(1.0_dp, 4.0_dp, 0.0_dp, 3.0_dp) == 0.0_dp)
  ! Beyond the cap (10^6 s): unknown rather than a silly number.
  call check('estimate_capped', progress_estimate(100.0_dp, 1.0e-9_dp, 0.0_dp, 1.0_dp) < 0.0_dp)

  ! ------------------------------------------- the end of a Hertz impact
  ! alpha'' = -c alpha^(3/2), alpha(0) = 0, alpha'(0) = V (the Hertz impact, k/M = c),
  ! integrated by RK4 (h = t_max/20000: the state to ~1e-12); from the state at
  ! 0.3 t_max, 0.9 t_max (loading) and 1.5 t_max (restitution, to separation) the
  ! estimate must give t_max = 0.4 B(0.4, 1/2) alpha_max/V with alpha_max =
  ! (5 V^2/(4 c))^(2/5) (energy), and 2 t_max to separation. The module's constant
  ! 1.4716 is that Beta value (1.471621...) rounded: 1.5e-5 relative, hence rtol 3e-5.
  alpha_max_exact = (5.0_dp*1.0_dp**2/(4.0_dp*2.0e4_dp))**0.4_dp                  ! V = 1 m/s, c = 2e4
  t_max_exact = 0.4_dp*gamma(0.4_dp)*gamma(0.5_dp)/gamma(0.9_dp)*alpha_max_exact/1.0_dp
  call check_close('hertz_constant_beta', 0.4_dp*gamma(0.4_dp)*gamma(0.5_dp)/gamma(0.9_dp), 1.4716_dp, 3.0e-5_dp)
  at = [0.3_dp, 0.9_dp, 1.5_dp]*t_max_exact
  call hertz_states(2.0e4_dp, 1.0_dp, at, alpha_at, v_at, t_max_ode, t_sep_ode)
  call check_close('hertz_ode_t_max', t_max_ode, t_max_exact, 1.0e-6_dp)
  call check_close('hertz_ode_separation', t_sep_ode, 2.0_dp*t_max_exact, 1.0e-6_dp)
  do k = 1, 3
    t_end_at(k) = progress_impact_end(0.25e-3_dp, alpha_at(k), -v_at(k), -1.0_dp, k == 3)   ! contact at 0.25 ms, downward
    t_hertz = 0.25e-3_dp + merge(2.0_dp, 1.0_dp, k == 3)*t_max_exact
    call check_close('hertz_end_from_state_'//integer_text(k), t_end_at(k), t_hertz, 3.0e-5_dp)
  end do
  call check('hertz_end_unknown_at_contact', progress_impact_end(0.0_dp, 0.0_dp, -1.0_dp, -1.0_dp, .false.) < 0.0_dp)
  call check('hertz_end_unknown_speeding_up', progress_impact_end(0.0_dp, 1.0e-4_dp, -1.1_dp, -1.0_dp, .false.) < 0.0_dp)

  ! ------------------------------------------------- forced on, no delay
  ! 24 steps of 50 ms: 1.2 s; alpha < 0 (no contact) for the first half.
  open(newunit=scratch, status='scratch', action='readwrite', form='formatted')
  call progress_configure(progress_on, delay=0.0_dp, unit=scratch)
  call check('on_enabled', progress_enabled())
  steps = 24
  allocate(before(steps), after(steps))
  call fake_run('fake', steps, 0.05_dp, 1.0e-4_dp)
  call read_back(count)
  print '(a)', 'what the forced run wrote (whole lines, not a terminal):'
  do k = 1, min(count, max_lines)
    print '(a)', '  '//trim(lines(k))
  end do
  call check('on_has_lines', count >= 2, 'lines: '//integer_text(count))
  call check('on_first_at_step_1', index(lines(1), 'visco2d: fake: step 1, t = 0.1000 ms, ~') == 1, trim(lines(1)))
  call check('on_first_no_alpha', index(lines(1), 'alpha') == 0, trim(lines(1)))
  call check('on_every_line_labelled', all([(index(lines(k), 'visco2d: fake: step ') == 1, k = 1, count)]))
  call check('on_whole_lines', all([(index(lines(k), achar(13)) == 0, k = 1, count)]), 'a carriage return in a log')
  call check('on_estimates', all([(index(lines(k), ' s left') > 0, k = 1, count - 1)]), trim(lines(max(1, count - 1))))
  call check('on_last_line_done', &
    index(lines(count), 'visco2d: fake: step 24, t = 2.4000 ms, alpha = 0.0120 mm, done in ') == 1, trim(lines(count)))
  ! Whole lines come at most once a second after the first: count - 1 step
  ! lines, the first at ~0 s, the others >= 1 s apart, within the run's time.
  call check('on_rate_limited', count - 1 <= 1 + int(elapsed_run/1.0_dp), &
             integer_text(count - 1)//' step lines in '//message_real(elapsed_run)//' s')

  ! ------------------------------------------ a delay: nothing before it
  ! 0.3 s delay, 12 steps of 50 ms: the first line at the first step whose
  ! clock reading (between `before` and `after` of that call) is >= 0.3 s.
  call progress_configure(progress_on, delay=0.3_dp, unit=scratch)
  steps = 12
  call fake_run('late', steps, 0.05_dp, 1.0e-4_dp)
  call read_back(count)
  first_shown = 0
  if (count >= 1) read(lines(1)(len('visco2d: late: step ') + 1:), *) first_shown
  call check('delay_shows_later', count >= 1 .and. first_shown > 1, 'first line: '//trim(lines(1)))
  if (first_shown > 1) then
    ! after_begin <= the module's start <= ... : guaranteed orderings only.
    call check('delay_not_before', after(first_shown) >= 0.3_dp, &
               'step '//integer_text(first_shown)//' shown '//message_real(after(first_shown))//' s after begin')
    call check('delay_not_late', before(first_shown - 1) < 0.3_dp, &
               'step '//integer_text(first_shown - 1)//' not shown at '//message_real(before(first_shown - 1))//' s')
  end if

  ! ------------------------------------------------- short runs stay silent
  call progress_configure(progress_on, delay=5.0_dp, unit=scratch)
  call fake_run('short', 5, 0.01_dp, 1.0e-4_dp)
  call read_back(count)
  call check('short_run_silent', count == 0, 'lines: '//integer_text(count)//' '//trim(lines(1)))

  call progress_configure(progress_off, delay=0.0_dp, unit=scratch)
  call check('off_disabled', .not. progress_enabled())
  call fake_run('off', 5, 0.01_dp, 1.0e-4_dp)
  call read_back(count)
  call check('off_silent', count == 0, 'lines: '//integer_text(count))

  ! auto with a unit that is not stderr: not a terminal anyone sees.
  call progress_configure(progress_auto, delay=0.0_dp, unit=scratch)
  call check('auto_file_disabled', .not. progress_enabled())
  call fake_run('auto', 5, 0.01_dp, 1.0e-4_dp)
  call read_back(count)
  call check('auto_file_silent', count == 0, 'lines: '//integer_text(count))

  ! A step without begin (or after end) writes nothing.
  call progress_configure(progress_on, delay=0.0_dp, unit=scratch)
  call progress_step(1, 1.0_dp, 1.0_dp)
  call progress_end()
  call read_back(count)
  call check('no_begin_silent', count == 0, 'lines: '//integer_text(count))

  ! ------------------------------------------------ a better end, later
  ! progress_expect_end moves the end the estimate aims at (0 left from it on),
  ! never past progress_begin's t_end, and ignores values <= 0. With no delay
  ! the first step is shown at once; its t is past the new end: "~0.0 s left";
  ! with the end unchanged, t has not advanced since the first step: "~? s left".
  call progress_configure(progress_on, delay=0.0_dp, unit=scratch)
  call expect_run(1.0_dp, 1.0e-4_dp, 2.0e-4_dp, count)
  call check('expect_end_moves_end', count == 2 .and. index(lines(1), ', ~0.0 s left') > 0, trim(lines(1)))
  call expect_run(1.0e-3_dp, 5.0_dp, 2.0e-3_dp, count)
  call check('expect_end_capped_by_begin', count == 2 .and. index(lines(1), ', ~0.0 s left') > 0, trim(lines(1)))
  call expect_run(1.0_dp, -1.0_dp, 2.0e-4_dp, count)
  call check('expect_end_ignores_negative', count == 2 .and. index(lines(1), ', ~? s left') > 0, trim(lines(1)))

  ! ---------------------------------------------- the cost of a step call
  ! Printed for the record (not asserted): off, and on but not yet due.
  call progress_configure(progress_off)
  cost_off = call_cost()
  call progress_configure(progress_on, delay=1000.0_dp, unit=scratch)
  call progress_begin('cost', 1.0_dp)
  cost_idle = call_cost()
  call progress_end()
  close(scratch)
  print '(a)', '| progress_step call       | ns per call |'
  print '(a)', '|--------------------------|-------------|'
  print '(a, f11.1, a)', '| off                      | ', 1.0e9_dp*cost_off, ' |'
  print '(a, f11.1, a)', '| on, before the delay     | ', 1.0e9_dp*cost_idle, ' |'

  call test_summary('test_progress')

contains

  !> A run of `n` steps of `wait` seconds each (busy wait), t = k dt, alpha
  !> (mm) = -1 for the first half (no contact), then (k - n/2) x 1e-3 mm;
  !> before(k)/after(k): seconds since progress_begin around step k's call,
  !> from clock readings taken just after/before progress_begin itself.
  subroutine fake_run(label, n, wait, dt)
    character(*), intent(in) :: label
    integer, intent(in) :: n
    real(dp), intent(in) :: wait, dt
    integer :: k
    integer(int64) :: now, until
    real(dp) :: alpha
    rewind(scratch)
    endfile(scratch)
    rewind(scratch)
    call system_clock(before_begin)
    call progress_begin(label, n*dt)
    call system_clock(after_begin)
    do k = 1, n
      call system_clock(now)
      until = now + nint(wait*real(rate, dp), int64)
      do while (now < until)
        call system_clock(now)
      end do
      alpha = -1.0_dp
      if (k > n/2) alpha = real(k - n/2, dp)*1.0e-3_dp
      if (k <= size(before)) before(k) = real(now - after_begin, dp)/real(rate, dp)
      call progress_step(k, k*dt, alpha)
      call system_clock(now)
      if (k <= size(after)) after(k) = real(now - before_begin, dp)/real(rate, dp)
    end do
    call progress_end()
    call system_clock(now)
    elapsed_run = real(now - before_begin, dp)/real(rate, dp)
  end subroutine fake_run

  !> begin(t_end), expect_end(expected), one step at t, end; the lines read back.
  subroutine expect_run(t_end, expected, t, count)
    real(dp), intent(in) :: t_end, expected, t
    integer, intent(out) :: count
    rewind(scratch)
    endfile(scratch)
    rewind(scratch)
    call progress_begin('expect', t_end)
    call progress_expect_end(expected)
    call progress_step(1, t, -1.0_dp)
    call progress_end()
    call read_back(count)
  end subroutine expect_run

  !> The Hertz impact alpha'' = -c max(alpha, 0)^(3/2), alpha(0) = 0,
  !> alpha'(0) = speed, by RK4: alpha and alpha' at the times `at`, the time
  !> of the maximum (alpha' = 0) and of separation (alpha = 0 again), both
  !> by linear interpolation within the step that crosses.
  subroutine hertz_states(c, speed, at, alpha, velocity, t_max, t_separation)
    real(dp), intent(in) :: c, speed, at(:)
    real(dp), intent(out) :: alpha(:), velocity(:), t_max, t_separation
    real(dp) :: y(2), y_new(2), z(2), h, time, scale
    integer :: next
    scale = 1.4716_dp*(5.0_dp*speed**2/(4.0_dp*c))**0.4_dp/speed
    h = scale/20000.0_dp
    y = [0.0_dp, speed]
    time = 0.0_dp
    next = 1
    t_max = -1.0_dp
    t_separation = -1.0_dp
    do while (time < 2.5_dp*scale)
      y_new = rk4_step(c, y, h)
      if (t_max < 0.0_dp .and. y(2) > 0.0_dp .and. y_new(2) <= 0.0_dp) t_max = time + h*y(2)/(y(2) - y_new(2))
      if (t_separation < 0.0_dp .and. y(1) > 0.0_dp .and. y_new(1) <= 0.0_dp) &
        t_separation = time + h*y(1)/(y(1) - y_new(1))
      do while (next <= size(at))
        if (at(next) > time + h) exit
        z = rk4_step(c, y, at(next) - time)      ! a step of the exact length to at(next)
        alpha(next) = z(1)
        velocity(next) = z(2)
        next = next + 1
      end do
      y = y_new
      time = time + h
    end do
  end subroutine hertz_states

  !> One RK4 step of length h of (alpha, alpha')' = (alpha', -c max(alpha, 0)^(3/2)).
  function rk4_step(c, y, h) result(y_new)
    real(dp), intent(in) :: c, y(2), h
    real(dp) :: y_new(2), k1(2), k2(2), k3(2), k4(2)
    k1 = hertz_rate(c, y)
    k2 = hertz_rate(c, y + 0.5_dp*h*k1)
    k3 = hertz_rate(c, y + 0.5_dp*h*k2)
    k4 = hertz_rate(c, y + h*k3)
    y_new = y + h/6.0_dp*(k1 + 2.0_dp*k2 + 2.0_dp*k3 + k4)
  end function rk4_step

  function hertz_rate(c, y) result(rate)
    real(dp), intent(in) :: c, y(2)
    real(dp) :: rate(2)
    rate = [y(2), -c*max(y(1), 0.0_dp)**1.5_dp]
  end function hertz_rate

  !> The scratch file's lines into lines(1:count).
  subroutine read_back(count)
    integer, intent(out) :: count
    integer :: status
    character(len=200) :: buffer
    lines = ''
    count = 0
    rewind(scratch)
    do
      read(scratch, '(a)', iostat=status) buffer
      if (status /= 0) exit
      count = count + 1
      if (count <= max_lines) lines(count) = buffer
    end do
    rewind(scratch)
    endfile(scratch)
    rewind(scratch)
  end subroutine read_back

  !> Seconds per progress_step call in the current state (10^6 calls).
  real(dp) function call_cost() result(seconds)
    integer, parameter :: calls = 1000000
    integer :: k
    integer(int64) :: start, finish
    call system_clock(start)
    do k = 1, calls
      call progress_step(k, real(k, dp)*1.0e-9_dp, -1.0_dp)
    end do
    call system_clock(finish)
    seconds = real(finish - start, dp)/real(rate, dp)/calls
  end function call_cost
end program test_progress
