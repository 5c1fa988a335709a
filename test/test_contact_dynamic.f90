!> Verification of impact on a rigid plate: Wilson-theta (theta = 1.4) with
!> the PLATE card (src/contact/visco2d_contact.f90, the contact part of
!> src/dynamics/visco2d_dynamic.f90), on the paper's sphere (MESH SPHERE, R = 36.6 mm),
!> on the default contact grid; where a bound was first set on the legacy
!> grid (GRID=LEGACY) its comment gives both grids' measured numbers.
!>
!>  1. Convergence, elastic sphere of Table 1 (E 18.11 MPa, nu 0.219,
!>     rho 756.85, V 0.9982 m/s, g 9.8): alpha_m, t_alpha, q_max, force_max
!>     for mesh levels 1-4 (dt 1e-5 s) and for dt 4e-5 .. 5e-6 s (level 3;
!>     alpha_m's error against dt = 1.25e-6 s must shrink as dt halves);
!>     observed orders p = log2(|f1 - f2| / |f2 - f3|) and Richardson values.
!>     Only alpha_m (the approach of the centre of mass, a whole-body
!>     quantity) is checked: its changes must shrink at least by 2 per
!>     halving (p >= 1). The peak times are sampled at dt and q is the
!>     pressure at the pole node, which jumps when a ring of nodes joins the
!>     contact: they are printed, not checked for an order.
!>  2. Restitution (elastic, level 3, RELEASE=YES, STOP AT=SEPARATION),
!>     SLIP and STICK: the energy books close (energy_absorbed_J against the
!>     whole-body energy split), where the deficit 1 - e^2 goes, and the
!>     contact duration against the Hertz duration 2.9432 alpha_m / V with
!>     the run's own alpha_m, and against an independent integration of the
!>     Hertz oscillator with gravity.
!>  3. Viscoelastic sphere of Table 2 (K 13.5 MPa, G 3.91 MPa, beta 203 1/s,
!>     drop 5 cm): q peaks before alpha by more than the time resolution
!>     (2 dt and the level 3 -> 4 change of the lead).
!>  4. The apples of Table 3 at 0.7 and 1.2 m/s: both maxima come sooner at
!>     the higher speed; t_alpha - t_q is reported with its resolution.
!>  5. A nearly incompressible sphere (nu 0.4999): FORMULATION BBAR does not
!>     lock (alpha_m follows Hertz's (1 - nu^2) scaling from nu = 0.49),
!>     STANDARD does; the plate force and pole pressure histories are
!>     examined for spikes when nodes join the contact (the run's maxima are
!>     reported beside smooth estimates), and the same impacts are run with
!>     RELEASE=YES to separation (contact chatter).
!>     The maxima must not be spikes: q >= 0 and q peaks with alpha on every
!>     level, force_max is the smooth peak and q_max the pressure at maximum
!>     deformation (to 3 %), and through rebound e <= 1 and the duration is
!>     Hertz's to 2 % -- which holds because the plate reactions are taken at
!>     t + theta dt, where Wilson-theta holds equilibrium (at t + dt they
!>     carried a stiff mode damped only by rho_inf = -0.778 per step: spikes of
!>     5x the force, and release/recapture chatter). The surface stress at
!>     the pole (q_surface) is taken at t + theta dt too: it peaks with alpha,
!>     reads q_max to 10 % and never pulls (at t + dt it spiked to 90.7 MPa).
!>  0. The Hertz reference keys are left out, with a reason, where they mean
!>     nothing (V = 4.9e-324 or 1e200 m/s, an absurd mass).
!> For an elastic body dissipated_J is round-off: the integrator's own loss
!> appears in balance_error_J (section 2).
!> Every number is printed in markdown tables. Decks are written to
!> build/test-tmp/test_contact_dynamic/. Release run time ~7 s; the longer
!> study (level 5, dt to 1.25e-6) is python/visco2d/convergence.py.
program test_contact_dynamic
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use visco2d_kinds, only: dp
  use visco2d_lapack, only: dgels
  use visco2d_error, only: error_t, error_text
  use visco2d_deck, only: deck_t, read_deck
  use visco2d_dynamic, only: solve_dynamic
  use visco2d_hertz, only: hertz_duration_constant, put_hertz_summary
  use visco2d_record, only: record_t
  use visco2d_expect, only: summary_value
  use visco2d_strings, only: integer_text, to_lower
  use visco2d_testing, only: check, check_close, check_text_contains, test_summary, write_deck, &
                             history_column, history_last
  implicit none

  character(*), parameter :: folder = 'build/test-tmp/test_contact_dynamic'
  integer, parameter :: line_length = 100

  !> One dynamic run: its record and the history columns used here.
  type :: run_t
    character(:), allocatable :: name
    type(record_t) :: record
    logical :: ok = .false.
    real(dp) :: seconds = 0.0_dp                 !< wall time of the run (printed only)
    real(dp) :: dt_ms = 0.0_dp
    integer :: nodes = 0, elements = 0
    real(dp), allocatable :: t(:), alpha(:), force(:), q(:), n(:)   !< ms, mm, N, MPa, contact nodes
  end type run_t

  !> The energy split of a run to separation (whole body, J).
  type :: split_t
    real(dp) :: e, v_in, v_out, v_cm, absorbed, input, mass, body_mass, ke0
    real(dp) :: vibration, strain, dissipated, loss, w_ext, w_grav, balance, books
  end type split_t

  integer :: clock_start, clock_rate, clock_end
  !> t_alpha - t_q (ms) of the elastic Table 1 runs at levels 3 and 4 (Hertz:
  !> both peak together), the discretization's own offset, from section 1.
  real(dp) :: elastic_lead(3:4) = 0.0_dp

  call system_clock(clock_start, clock_rate)
  call execute_command_line('mkdir -p '//folder)
  call test_hertz_constants()
  call test_hertz_guard()
  call test_convergence()
  call test_restitution()
  call test_table2()
  call test_apples()
  call test_incompressible()
  call system_clock(clock_end)
  print '(a, f0.1, a)', 'test_contact_dynamic: wall time ', real(clock_end - clock_start, dp)/clock_rate, ' s'
  call test_summary('test_contact_dynamic')

contains

  ! ---------------------------------------------------------------- decks

  !> The elastic sphere of Table 1 dropping on the plate: level, dt, end time,
  !> the PLATE card and extra cards; nu and FORMULATION may be changed.
  function table1_deck(level, dt, tend, plate, extra, poisson, formulation) result(lines)
    integer, intent(in) :: level
    real(dp), intent(in) :: dt, tend
    character(*), intent(in) :: plate
    character(*), intent(in), optional :: extra, poisson, formulation
    character(len=line_length), allocatable :: lines(:)
    character(:), allocatable :: nu
    nu = '0.219'
    if (present(poisson)) nu = poisson
    lines = [character(len=line_length) :: 'ANALYSIS DYNAMIC', 'GEOMETRY AXISYMMETRIC']
    if (present(formulation)) call add(lines, 'FORMULATION '//formulation)
    call add(lines, 'MATERIAL apple ELASTIC E=18.11e6 NU='//nu//' RHO=756.85')
    call add(lines, 'MESH SPHERE R=0.0366 LEVEL='//integer_text(level))
    call add(lines, 'INITIAL VZ=-0.9982 AZ=-9.8')
    call add(lines, 'GRAVITY G=9.8')
    call add(lines, 'WILSON THETA=1.4')
    call add(lines, 'TIME DT='//real_text(dt)//' TEND='//real_text(tend))
    call add(lines, plate)
    if (present(extra)) call add(lines, extra)
  end function table1_deck

  subroutine add(lines, text)
    character(len=line_length), allocatable, intent(inout) :: lines(:)
    character(*), intent(in) :: text
    character(len=line_length), allocatable :: longer(:)
    allocate(longer(size(lines) + 1))
    longer(1:size(lines)) = lines
    longer(size(lines) + 1) = text
    call move_alloc(longer, lines)
  end subroutine add

  !> Write TITLE + body + END, read it and run it (a failed check if it does not run).
  function run_case(name, body) result(run)
    character(*), intent(in) :: name
    character(len=line_length), intent(in) :: body(:)
    type(run_t) :: run
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    character(:), allocatable :: path
    character(len=line_length), allocatable :: deck_lines(:)
    integer :: start, finish, rate
    call system_clock(start, rate)
    run%name = name
    path = folder//'/'//name//'.inp'
    allocate(deck_lines(size(body) + 2))
    deck_lines(1) = 'TITLE '//name
    deck_lines(2:size(body) + 1) = body
    deck_lines(size(body) + 2) = 'END'
    call write_deck(path, deck_lines)
    call read_deck(path, deck, error)
    if (.not. allocated(error)) call solve_dynamic(deck, run%record, error)
    if (allocated(error)) then
      call check('run_'//name, .false., error_text(error))
      allocate(run%t(0), run%alpha(0), run%force(0), run%q(0), run%n(0))
      return
    end if
    run%ok = .true.
    run%dt_ms = 1.0e3_dp*deck%stages(1)%dt
    run%nodes = deck%mesh%nnode
    run%elements = deck%mesh%nelem
    run%t = history_column(run%record, 't_ms')
    run%alpha = history_column(run%record, 'alpha_mm')
    run%force = history_column(run%record, 'force_N')
    run%q = history_column(run%record, 'q_MPa')
    run%n = history_column(run%record, 'n_contact')
    call system_clock(finish)
    run%seconds = real(finish - start, dp)/rate
  end function run_case

  !> A real summary value of a run (NaN, and a failed check, if absent).
  real(dp) function value_of(run, key) result(x)
    type(run_t), intent(in) :: run
    character(*), intent(in) :: key
    character(:), allocatable :: text
    integer :: status
    x = ieee_value(1.0_dp, ieee_quiet_nan)
    text = summary_value(run%record, key)
    if (len(text) == 0) then
      call check(run%name//'_has_'//key, .false., 'no summary key '//key)
      return
    end if
    read(text, *, iostat=status) x
    if (status /= 0) call check(run%name//'_reads_'//key, .false., 'not a number: '//text)
  end function value_of

  ! ---------------------------------------------------------------- analysis helpers

  !> The peak of a sampled curve refined by the parabola through the largest
  !> sample and its two neighbours (removes most of the O(dt^2) sampling error).
  subroutine parabola_peak(t, f, t_peak, f_peak)
    real(dp), intent(in) :: t(:), f(:)
    real(dp), intent(out) :: t_peak, f_peak
    integer :: i
    real(dp) :: shift, curvature
    i = maxloc(f, dim=1)
    t_peak = t(i)
    f_peak = f(i)
    if (i == 1 .or. i == size(f)) return
    curvature = f(i - 1) - 2.0_dp*f(i) + f(i + 1)
    if (curvature >= 0.0_dp) return
    shift = 0.5_dp*(f(i - 1) - f(i + 1))/curvature
    t_peak = t(i) + shift*(t(i + 1) - t(i))
    f_peak = f(i) - 0.25_dp*(f(i - 1) - f(i + 1))*shift
  end subroutine parabola_peak

  !> The ring-arrival interval near a peak at t_end: the mean time between the
  !> last three increases of the contact-node count at or before t_end (-1 if
  !> there are fewer than three).
  real(dp) function ring_interval(t, n, t_end) result(interval)
    real(dp), intent(in) :: t(:), n(:), t_end
    real(dp) :: times(size(t))
    integer :: i, count
    count = 0
    do i = 2, size(t)
      if (n(i) > n(i - 1) .and. t(i) <= t_end + 1.0e-9_dp) then
        count = count + 1
        times(count) = t(i)
      end if
    end do
    interval = -1.0_dp
    if (count >= 3) interval = 0.5_dp*(times(count) - times(count - 2))
  end function ring_interval

  !> Does the contact-node count change within |t - t0| <= half_width?
  logical function ring_change_near(t, n, t0, half_width) result(near)
    real(dp), intent(in) :: t(:), n(:), t0, half_width
    integer :: i
    near = .false.
    do i = 2, size(t)
      if (n(i) /= n(i - 1) .and. abs(t(i) - t0) <= half_width + 1.0e-9_dp) near = .true.
    end do
  end function ring_change_near

  !> The largest |f(i) - f(i-1)| over the steps i within half_width of t0
  !> where the contact set changes (n(i) /= n(i-1)); 0 if there is none.
  real(dp) function ring_jump_near(t, n, f, t0, half_width) result(jump)
    real(dp), intent(in) :: t(:), n(:), f(:), t0, half_width
    integer :: i
    jump = 0.0_dp
    do i = 2, size(t)
      if (n(i) /= n(i - 1) .and. abs(t(i) - t0) <= half_width + 1.0e-9_dp) jump = max(jump, abs(f(i) - f(i - 1)))
    end do
  end function ring_jump_near

  !> Contact-set chatter: the number of releases (decreases of the contact-node
  !> count) before t_end, and the number of increases after the first release.
  subroutine chatter(t, n, t_end, early_releases, recaptures)
    real(dp), intent(in) :: t(:), n(:), t_end
    integer, intent(out) :: early_releases, recaptures
    integer :: i
    logical :: released
    early_releases = 0
    recaptures = 0
    released = .false.
    do i = 2, size(t)
      if (n(i) < n(i - 1)) then
        released = .true.
        if (t(i) < t_end) early_releases = early_releases + 1
      else if (n(i) > n(i - 1) .and. released) then
        recaptures = recaptures + 1
      end if
    end do
  end subroutine chatter

  !> The peak of the centred moving average of f over a window of the given width.
  subroutine moving_average_peak(t, f, width, f_peak, t_peak)
    real(dp), intent(in) :: t(:), f(:), width
    real(dp), intent(out) :: f_peak, t_peak
    integer :: i
    real(dp) :: mean
    f_peak = -huge(1.0_dp)
    t_peak = 0.0_dp
    do i = 1, size(t)
      mean = sum(f, mask=abs(t - t(i)) <= 0.5_dp*width + 1.0e-9_dp)/ &
             count(abs(t - t(i)) <= 0.5_dp*width + 1.0e-9_dp)
      if (mean > f_peak) then
        f_peak = mean
        t_peak = t(i)
      end if
    end do
  end subroutine moving_average_peak

  !> The least-squares polynomial of the given degree through (t, f),
  !> evaluated at t (LAPACK dgels on x = 2 t / max(t) - 1).
  function poly_fit(t, f, degree) result(fit)
    real(dp), intent(in) :: t(:), f(:)
    integer, intent(in) :: degree
    real(dp) :: fit(size(t))
    real(dp) :: x(size(t)), a(size(t), degree + 1), b(size(t), 1), v(size(t), degree + 1)
    real(dp), allocatable :: work(:)
    integer :: m, k, info
    m = size(t)
    x = 2.0_dp*t/maxval(t) - 1.0_dp
    do k = 0, degree
      v(:, k + 1) = x**k
    end do
    a = v
    b(:, 1) = f
    allocate(work(64*(m + degree + 1)))
    call dgels('N', m, degree + 1, 1, a, m, b, m, work, size(work), info)
    fit = matmul(v, b(1:degree + 1, 1))
    if (info /= 0) fit = ieee_value(1.0_dp, ieee_quiet_nan)
  end function poly_fit

  !> Contact duration of the Hertz oscillator with gravity,
  !> alpha'' = g - kappa alpha^(3/2) (alpha > 0), alpha(0) = 0, alpha'(0) = V,
  !> with kappa such that alpha reaches alpha_m: (2/5) kappa alpha_m^(5/2) = V^2/2 + g alpha_m.
  !> Classical RK4 with 40000 steps per alpha_m / V (error far below 1e-6),
  !> the return to alpha = 0 interpolated linearly.
  real(dp) function hertz_duration(speed, gravity, alpha_m) result(duration)
    real(dp), intent(in) :: speed, gravity, alpha_m
    real(dp) :: kappa, h, y(2), k1(2), k2(2), k3(2), k4(2), previous, time
    kappa = (0.5_dp*speed**2 + gravity*alpha_m)/(0.4_dp*alpha_m**2.5_dp)
    h = alpha_m/speed/40000.0_dp
    y = [0.0_dp, speed]
    time = 0.0_dp
    do
      previous = y(1)
      k1 = hertz_slope(y, gravity, kappa)
      k2 = hertz_slope(y + 0.5_dp*h*k1, gravity, kappa)
      k3 = hertz_slope(y + 0.5_dp*h*k2, gravity, kappa)
      k4 = hertz_slope(y + h*k3, gravity, kappa)
      y = y + h/6.0_dp*(k1 + 2.0_dp*k2 + 2.0_dp*k3 + k4)
      time = time + h
      if (y(1) < 0.0_dp) exit
    end do
    duration = time - h*y(1)/(y(1) - previous)
  end function hertz_duration

  !> (alpha', alpha'') of the Hertz oscillator with gravity.
  pure function hertz_slope(state, gravity, kappa) result(rate)
    real(dp), intent(in) :: state(2), gravity, kappa
    real(dp) :: rate(2)
    rate = [state(2), gravity - kappa*max(state(1), 0.0_dp)**1.5_dp]
  end function hertz_slope

  !> log2(|f1 - f2| / |f2 - f3|).
  real(dp) function order_of(f1, f2, f3) result(p)
    real(dp), intent(in) :: f1, f2, f3
    p = log(abs(f1 - f2)/abs(f2 - f3))/log(2.0_dp)
  end function order_of

  ! ---------------------------------------------------------------- text

  function fx(x, decimals) result(text)
    real(dp), intent(in) :: x
    integer, intent(in) :: decimals
    character(:), allocatable :: text
    character(len=40) :: buffer, form
    write(form, '(a, i0, a)') '(f30.', decimals, ')'
    write(buffer, form) x
    text = trim(adjustl(buffer))
  end function fx

  function ex(x) result(text)
    real(dp), intent(in) :: x
    character(:), allocatable :: text
    character(len=40) :: buffer
    write(buffer, '(es11.4)') x
    text = trim(adjustl(buffer))
  end function ex

  function real_text(x) result(text)
    real(dp), intent(in) :: x
    character(:), allocatable :: text
    character(len=40) :: buffer
    write(buffer, '(es12.5)') x
    text = trim(adjustl(buffer))
  end function real_text

  ! ---------------------------------------------------------------- 0. constants

  !> The Hertz duration constant of the library and the oscillator used below:
  !> 2 t_m V / alpha_m = 2 (2/5) B(2/5, 1/2) exactly (energy integral of
  !> m alpha'' = -k alpha^(3/2)); the library prints 1.4716 (5 digits, rtol 5e-5).
  subroutine test_hertz_constants()
    real(dp) :: exact
    exact = 2.0_dp*0.4_dp*gamma(0.4_dp)*gamma(0.5_dp)/gamma(0.9_dp)
    call check_close('hertz_duration_constant', hertz_duration_constant, exact, 5.0e-5_dp)
    call check_close('hertz_oscillator_without_gravity', hertz_duration(1.0_dp, 0.0_dp, 1.0e-3_dp), &
                     exact*1.0e-3_dp, 1.0e-6_dp)
  end subroutine test_hertz_constants

  !> The Hertz reference keys are left out, with hertz_reference saying why,
  !> when they would mean nothing: V = 4.9e-324 m/s (alpha_m = 0, below the
  !> round-off of the node positions), V = 1e200 m/s (not small against the
  !> wave speed sqrt(E/rho) = 155 m/s; V^2 would overflow), and a mass of
  !> 1e300 kg (alpha_m not small against R). At V = 0.9982 m/s and M = 0.155 kg
  !> they are there, finite, and there is no hertz_reference key. No summary
  !> value is Infinity or NaN.
  subroutine test_hertz_guard()
    real(dp) :: speeds(4)
    real(dp), parameter :: masses(4) = [0.155_dp, 0.155_dp, 1.0e300_dp, 0.155_dp]
    character(len=8), parameter :: names(4) = ['tiny    ', 'overflow', 'heavy   ', 'table1  ']
    type(deck_t) :: deck
    type(record_t) :: record
    type(error_t), allocatable :: error
    character(:), allocatable :: path, text
    integer :: k, i
    logical :: finite
    ! The smallest positive double, 4.9e-324 (a literal that small underflows in the compiler).
    speeds = [nearest(0.0_dp, 1.0_dp), 1.0e200_dp, 0.9982_dp, 0.9982_dp]
    path = folder//'/hertz_guard.inp'
    call write_deck(path, [character(len=line_length) :: 'TITLE Hertz guard', 'ANALYSIS DYNAMIC', &
      'GEOMETRY AXISYMMETRIC', 'MATERIAL apple ELASTIC E=18.11e6 NU=0.219 RHO=756.85', &
      'MESH SPHERE R=0.0366 LEVEL=1', 'INITIAL VZ=-0.9982', 'TIME DT=1e-5 TEND=1e-4', 'PLATE Z=0', 'END'])
    call read_deck(path, deck, error)
    if (allocated(error)) then
      call check('hertz_guard_deck_reads', .false., error_text(error))
      return
    end if
    do k = 1, size(speeds)
      record = record_t()
      call put_hertz_summary(deck, record, masses(k), -speeds(k))
      text = summary_value(record, 'hertz_reference')
      if (k < 4) then
        call check('hertz_guard_'//trim(names(k))//'_no_keys', len(summary_value(record, 'hertz_alpha_max_mm')) == 0 &
                   .and. len(summary_value(record, 'hertz_t_alpha_max_ms')) == 0)
        call check('hertz_guard_'//trim(names(k))//'_says_why', index(text, 'none: ') == 1, text)
        print '(a)', 'hertz_reference = '//text
      else
        call check('hertz_guard_table1_keys', len(summary_value(record, 'hertz_alpha_max_mm')) > 0 .and. &
                   len(text) == 0, text)
      end if
      finite = .true.
      do i = 1, record%nsummary
        if (index(record%summary(i)%key, 'hertz_reference') == 1) cycle
        text = to_lower(record%summary(i)%value)
        if (index(text, 'inf') > 0 .or. index(text, 'nan') > 0) finite = .false.
      end do
      call check('hertz_guard_'//trim(names(k))//'_finite_values', finite)
    end do
  end subroutine test_hertz_guard

  ! ---------------------------------------------------------------- 1. convergence

  subroutine test_convergence()
    real(dp), parameter :: dts(4) = [4.0e-5_dp, 2.0e-5_dp, 1.0e-5_dp, 5.0e-6_dp], dt_reference = 1.25e-6_dp
    type(run_t) :: mesh(4), steps(4)
    real(dp) :: alpha(4), alpha_dt(4), alpha_dt_raw(4), t_peak, p_mesh(2), p_dt(2), alpha_inf, alpha_dt_inf
    real(dp) :: bound_dt, force(4), alpha_reference, error_dt(4)
    type(run_t) :: reference
    integer :: l

    print '(a)', ''
    print '(a)', '### 1. Convergence: elastic sphere of Table 1 (V 0.9982 m/s, STICK, stop at maximum deformation)'
    do l = 1, 4
      mesh(l) = run_case('table1_level'//integer_text(l), table1_deck(l, 1.0e-5_dp, 4.0e-3_dp, 'PLATE Z=0'))
      if (.not. mesh(l)%ok) return
    end do
    do l = 1, 4
      if (l == 3) then
        steps(l) = mesh(3)
      else
        steps(l) = run_case('table1_dt'//integer_text(l), table1_deck(3, dts(l), 4.0e-3_dp, 'PLATE Z=0'))
        if (.not. steps(l)%ok) return
      end if
    end do
    reference = run_case('table1_dt_reference', table1_deck(3, dt_reference, 4.0e-3_dp, 'PLATE Z=0'))
    if (.not. reference%ok) return

    print '(a)', ''
    print '(a)', 'Mesh refinement (dt = 1e-5 s). q_max is at the pole node; min q shows the consistent'// &
                 ' projection going negative on coarse meshes.'
    print '(a)', ''
    print '(a)', '| level | elements | nodes | alpha_max mm | t_alpha ms | q_max MPa | t_q ms | min q MPa |'// &
                 ' q_surface_max MPa | force_max N | t_force ms | contact nodes | Hertz alpha mm | Hertz q MPa |'// &
                 ' Hertz F N | run s |'
    print '(a)', '|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|'
    do l = 1, 4
      alpha(l) = value_of(mesh(l), 'alpha_max_mm')
      force(l) = value_of(mesh(l), 'force_max_N')
      print '(a)', '| '//integer_text(l)//' | '//integer_text(mesh(l)%elements)//' | '//integer_text(mesh(l)%nodes)//' | ' &
        //fx(alpha(l), 4)//' | '// &
        fx(value_of(mesh(l), 't_alpha_max_ms'), 3)//' | '//fx(value_of(mesh(l), 'q_max_MPa'), 3)//' | '// &
        fx(value_of(mesh(l), 't_q_max_ms'), 3)//' | '//fx(minval(mesh(l)%q), 3)//' | '// &
        fx(value_of(mesh(l), 'q_surface_max_MPa'), 3)//' | '//fx(force(l), 2)//' | '// &
        fx(value_of(mesh(l), 't_force_max_ms'), 3)//' | '//summary_value(mesh(l)%record, 'contact_nodes_max')// &
        ' | '//fx(value_of(mesh(l), 'hertz_alpha_max_mm'), 4)//' | '//fx(value_of(mesh(l), 'hertz_q_max_MPa'), 3)// &
        ' | '//fx(value_of(mesh(l), 'hertz_force_max_N'), 1)//' | '//fx(mesh(l)%seconds, 2)//' |'
    end do
    do l = 3, 4
      elastic_lead(l) = value_of(mesh(l), 't_alpha_max_ms') - value_of(mesh(l), 't_q_max_ms')
    end do
    p_mesh(1) = order_of(alpha(1), alpha(2), alpha(3))
    p_mesh(2) = order_of(alpha(2), alpha(3), alpha(4))
    alpha_inf = alpha(4) + (alpha(4) - alpha(3))/(2.0_dp**p_mesh(2) - 1.0_dp)
    print '(a)', ''
    print '(a)', '| alpha_m, mesh | value |'
    print '(a)', '|---|---|'
    print '(a)', '| changes L1->2, L2->3, L3->4 (mm) | '//ex(alpha(2) - alpha(1))//', '//ex(alpha(3) - alpha(2))// &
                 ', '//ex(alpha(4) - alpha(3))//' |'
    print '(a)', '| observed order p (L1,2,3) | '//fx(p_mesh(1), 2)//' |'
    print '(a)', '| observed order p (L2,3,4) | '//fx(p_mesh(2), 2)//' |'
    print '(a)', '| Richardson alpha_m (L2,3,4) mm | '//fx(alpha_inf, 4)//' |'
    print '(a)', '| level 4 vs Richardson | '//fx(100.0_dp*(alpha(4)/alpha_inf - 1.0_dp), 2)//' % |'
    print '(a)', '| level 3 vs level 4 | '//fx(100.0_dp*(alpha(3)/alpha(4) - 1.0_dp), 2)//' % |'
    print '(a)', '| level 1 (the paper''s 88 elements) vs level 4 | '//fx(100.0_dp*(alpha(1)/alpha(4) - 1.0_dp), 2)// &
                 ' % |'
    print '(a)', '| level 1 vs Richardson | '//fx(100.0_dp*(alpha(1)/alpha_inf - 1.0_dp), 2)//' % |'
    print '(a)', '| Richardson vs Hertz (level-4 mass) | '//fx(100.0_dp*(alpha_inf/value_of(mesh(4), &
                 'hertz_alpha_max_mm') - 1.0_dp), 2)//' % |'
    print '(a)', '| force_max level 3 vs level 4 | '//fx(100.0_dp*(force(3)/force(4) - 1.0_dp), 3)//' % |'

    ! Bilinear elements converge at O(h^2) in displacement; a contact edge
    ! resolved only to one node ring can lower that to O(h), never below: so
    ! each halving of h must at least halve the change of alpha_m (p >= 1).
    ! q (the pole's reaction at t + theta dt over its row of the lumped
    ! boundary mass) is never negative and peaks with alpha, within the
    ! arrival interval of a node ring (0.1 ms at these levels), on every level.
    do l = 1, 4
      call check('table1_level'//integer_text(l)//'_q_never_negative', minval(mesh(l)%q) >= 0.0_dp, &
                 'min q = '//fx(minval(mesh(l)%q), 3)//' MPa')
      call check_close('table1_level'//integer_text(l)//'_q_peaks_with_alpha', value_of(mesh(l), 't_q_max_ms'), &
                       value_of(mesh(l), 't_alpha_max_ms'), 0.0_dp, 0.1_dp)
    end do
    call check('table1_mesh_alpha_changes_halve', abs(alpha(2) - alpha(1)) >= 2.0_dp*abs(alpha(3) - alpha(2)) .and. &
               abs(alpha(3) - alpha(2)) >= 2.0_dp*abs(alpha(4) - alpha(3)), 'p(1,2,3) = '//fx(p_mesh(1), 3)// &
               ', p(2,3,4) = '//fx(p_mesh(2), 3))
    ! With p >= 1 the level-4 change is at most half the level 2->3 change
    ! (0.146 % on the contact grid, measured; 1.8 % on the legacy grid, where
    ! the bound was 1 %): level 3 must be within 0.1 % of level 4 (measured
    ! 0.023 %; the legacy grid's level 3 was 0.39 % off).
    call check_close('table1_mesh_level3_within_0.1pc_of_level4', alpha(3), alpha(4), 0.001_dp)
    ! The plate force is a whole-body quantity too (M (g - alpha'')), but its
    ! peak carries the ringing of the contact (levels 1-4: 197.9, 192.8, 192.4,
    ! 193.3 N, not monotone): held to the 1 % of the legacy grid (measured 0.44 %).
    call check_close('table1_mesh_force_level3_within_1pc_of_level4', force(3), force(4), 0.01_dp)

    print '(a)', ''
    print '(a)', 'Time-step refinement (level 3). alpha_m is the largest sample; "parabola" refines it by the'// &
                 ' parabola through the three samples around it (the O(dt^2) sampling error of a maximum).'
    print '(a)', ''
    print '(a)', '| dt s | alpha_max mm | alpha (parabola) mm | t_alpha ms | q_max MPa | t_q ms | force_max N |'// &
                 ' balance_error J/rad | run s |'
    print '(a)', '|---|---|---|---|---|---|---|---|---|'
    do l = 1, 4
      alpha_dt_raw(l) = value_of(steps(l), 'alpha_max_mm')
      call parabola_peak(steps(l)%t, steps(l)%alpha, t_peak, alpha_dt(l))
      print '(a)', '| '//ex(dts(l))//' | '//fx(alpha_dt_raw(l), 6)//' | '//fx(alpha_dt(l), 6)//' | '// &
        fx(value_of(steps(l), 't_alpha_max_ms'), 3)//' | '//fx(value_of(steps(l), 'q_max_MPa'), 3)//' | '// &
        fx(value_of(steps(l), 't_q_max_ms'), 3)//' | '//fx(value_of(steps(l), 'force_max_N'), 2)//' | '// &
        ex(value_of(steps(l), 'balance_error_J'))//' | '//fx(steps(l)%seconds, 2)//' |'
    end do
    p_dt(1) = order_of(alpha_dt(1), alpha_dt(2), alpha_dt(3))
    p_dt(2) = order_of(alpha_dt(2), alpha_dt(3), alpha_dt(4))
    alpha_dt_inf = alpha_dt(4) + (alpha_dt(4) - alpha_dt(3))/(2.0_dp**p_dt(2) - 1.0_dp)
    print '(a)', ''
    print '(a)', '| alpha_m (parabola), dt | value |'
    print '(a)', '|---|---|'
    print '(a)', '| changes 4e-5->2e-5->1e-5->5e-6 (mm) | '//ex(alpha_dt(2) - alpha_dt(1))//', '// &
                 ex(alpha_dt(3) - alpha_dt(2))//', '//ex(alpha_dt(4) - alpha_dt(3))//' |'
    print '(a)', '| observed order p (4e-5, 2e-5, 1e-5) | '//fx(p_dt(1), 2)//' |'
    print '(a)', '| observed order p (2e-5, 1e-5, 5e-6) | '//fx(p_dt(2), 2)//' |'
    print '(a)', '| Richardson alpha_m mm | '//fx(alpha_dt_inf, 6)//' |'
    print '(a)', '| dt = 1e-5 vs Richardson | '//fx(100.0_dp*(alpha_dt(3)/alpha_dt_inf - 1.0_dp), 4)//' % |'
    print '(a)', '| raw maxima: observed order p (2e-5, 1e-5, 5e-6) | '// &
                 fx(order_of(alpha_dt_raw(2), alpha_dt_raw(3), alpha_dt_raw(4)), 2)//' |'

    ! Wilson-theta converges (O(dt^2), contact events at O(dt)): the error
    ! of alpha_m against a reference run at dt = 1.25e-6 must shrink at every
    ! halving of dt. (The check was that the changes between successive dt
    ! shrink. On the GRADE=2.5 contact grid they did over 4e-5 .. 5e-6:
    ! 2.55e-4, 1.52e-4, 1.24e-4 mm, though not beyond: 1.30e-4 mm from 8e-5
    ! to 4e-5, and 3.5e-5 then 4.2e-5 mm from 5e-6 to 1.25e-6. On the GRADE=4.5
    ! grid, 17 nodes join the contact at level 3 (9 before), each at the
    ! step after it touches, an O(dt) timing error whose size and sign shift
    ! irregularly as dt halves: the changes are 1.30e-4, 4.50e-4, 0.84e-4 mm,
    ! p = -1.80, 2.42, while the errors against dt = 1.25e-6 fall steadily,
    ! 7.49e-4, 6.19e-4, 1.69e-4, 0.85e-4 mm (GRADE=2.5: 7.38e-4, 3.53e-4,
    ! 2.01e-4, 0.77e-4 mm); measured offline, |alpha(2.5e-6) - alpha(1.25e-6)|
    ! = 2.2e-5 mm, a quarter of the smallest error checked. Level 4 on the new
    ! grid has monotone changes too: 6.6e-4, 3.6e-4, 1.3e-4 mm.)
    call parabola_peak(reference%t, reference%alpha, t_peak, alpha_reference)
    error_dt = abs(alpha_dt - alpha_reference)
    print '(a)', '| errors against dt = 1.25e-6 (mm): 4e-5, 2e-5, 1e-5, 5e-6 | '//ex(error_dt(1))//', '// &
                 ex(error_dt(2))//', '//ex(error_dt(3))//', '//ex(error_dt(4))//' |'
    call check('table1_dt_alpha_errors_shrink', error_dt(1) > error_dt(2) .and. error_dt(2) > error_dt(3) .and. &
               error_dt(3) > error_dt(4), 'errors '//ex(error_dt(1))//', '//ex(error_dt(2))//', '// &
               ex(error_dt(3))//', '//ex(error_dt(4))//' mm (changes: p = '//fx(p_dt(1), 3)//', '//fx(p_dt(2), 3)//')')
    ! The paper's dt = 1e-5 cannot decide the mesh checks above. With p >= 1
    ! its error is at most bound_dt = 2 |alpha(5e-6) - alpha(1e-5)| (2.5e-4 mm,
    ! 0.024 %, measured; offline down to dt = 1.25e-6 alpha_m grows by 2.0e-4
    ! mm at level 3 and 1.75e-4 mm at level 4, the same sign, so the level 3->4
    ! change moves from -2.38e-4 to -2.64e-4 mm). On the legacy grid this bound
    ! was below a tenth of the level-3 mesh error |alpha_4 - alpha_3| (4.1e-3
    ! mm); the contact grid's level 3 is 17 times closer (2.4e-4 mm, 0.023 %),
    ! as close in space as dt = 1e-5 is in time, so a tenth cannot hold there.
    ! What must hold: the halving of the changes survives the whole dt error
    ! added to the level 3->4 change (errors of one sign, each at most
    ! bound_dt, move a difference by at most bound_dt).
    bound_dt = 2.0_dp*abs(alpha_dt(4) - alpha_dt(3))
    call check('table1_dt_error_cannot_decide_the_mesh_halving', &
               abs(alpha(3) - alpha(2)) >= 2.0_dp*(abs(alpha(4) - alpha(3)) + bound_dt), &
               'dt bound '//ex(bound_dt)//' mm, mesh changes '//ex(abs(alpha(3) - alpha(2)))//', '// &
               ex(abs(alpha(4) - alpha(3)))//' mm')
    print '(a)', 'dt = 1e-5 error bound 2 |alpha(5e-6) - alpha(1e-5)| = '//ex(bound_dt)//' mm against the level'// &
                 ' 3 -> 4 mesh change '//ex(abs(alpha(4) - alpha(3)))//' mm'
  end subroutine test_convergence

  ! ---------------------------------------------------------------- 2. restitution

  type(split_t) function energy_split(run) result(split)
    type(run_t), intent(in) :: run
    split%e = value_of(run, 'coefficient_of_restitution')
    split%v_in = value_of(run, 'impact_velocity_m_s')
    split%v_out = value_of(run, 'rebound_velocity_m_s')
    split%absorbed = value_of(run, 'energy_absorbed_J')
    split%mass = value_of(run, 'mass_kg')
    split%body_mass = value_of(run, 'body_mass_kg')
    split%input = 0.5_dp*split%mass*split%v_in**2
    ! Whole-body energies (the axisymmetric energy_basis) from the last history row (full precision).
    split%ke0 = run%record%history(index_of(run, 'kinetic_J'), 1)
    split%v_cm = history_last(run%record, 'vz_cm_m_s')
    split%vibration = history_last(run%record, 'kinetic_J') - 0.5_dp*split%mass*split%v_cm**2
    split%strain = history_last(run%record, 'strain_J')
    split%dissipated = history_last(run%record, 'dissipated_J')
    split%loss = history_last(run%record, 'contact_loss_J')
    split%w_ext = history_last(run%record, 'external_work_J')
    split%w_grav = history_last(run%record, 'gravity_work_J')
    split%balance = history_last(run%record, 'balance_error_J')
    ! The books: the run's energy balance, kinetic + internal + loss = initial
    ! kinetic + works + balance, rearranged for 1/2 M (V0^2 - v_out^2), less
    ! the pre-contact fall (KE0 - 1/2 M V^2; zero here, contact at t = 0).
    split%books = split%vibration + split%strain + split%dissipated + split%loss - split%w_ext - split%w_grav - &
                  split%balance - (split%ke0 - split%input)
  end function energy_split

  subroutine test_restitution()
    character(len=5), parameter :: modes(2) = ['SLIP ', 'STICK']
    type(run_t) :: runs(2)
    type(split_t) :: split
    real(dp) :: alpha_m, duration, hertz_own, hertz_g, hertz_ref, t_alpha, v_in
    integer :: k, early, recaptured
    character(:), allocatable :: tag

    print '(a)', ''
    print '(a)', '### 2. Restitution and energy (elastic, level 3, dt 1e-5, RELEASE=YES, STOP AT=SEPARATION)'
    do k = 1, 2
      runs(k) = run_case('restitution_'//trim(modes(k)), table1_deck(3, 1.0e-5_dp, 6.0e-3_dp, 'PLATE Z=0 '// &
                         trim(modes(k))//' RELEASE=YES', 'STOP AT=SEPARATION'))
      if (.not. runs(k)%ok) return
    end do
    print '(a)', ''
    print '(a)', 'Energies in J for the whole body (energy_basis = whole body). absorbed = 1/2 M (V^2 - v_out^2) ='// &
                 ' vibration left in the body (kinetic - 1/2 M v_cm^2, and strain) + contact loss (kinetic energy of'// &
                 ' nodes stopped by the plate) + work against gravity (-W_g: the centre of mass is higher at'// &
                 ' separation than at first contact) + work of the plate (-W_ext) + what the balance does not'// &
                 ' account for (-balance: Wilson-theta''s algorithmic loss and the contact events) + dissipated.'
    print '(a)', ''
    print '(a)', '| plate | e | 1 - e^2 | 1/2 M V^2 | absorbed | vib. kinetic | strain | dissipated | contact loss |'// &
                 ' -W_gravity | -W_plate | -balance | books - absorbed |'
    print '(a)', '|---|---|---|---|---|---|---|---|---|---|---|---|---|'
    do k = 1, 2
      split = energy_split(runs(k))
      print '(a)', '| '//trim(modes(k))//' | '//fx(split%e, 6)//' | '//ex(1.0_dp - split%e**2)//' | '// &
        ex(split%input)//' | '//ex(split%absorbed)//' | '//ex(split%vibration)//' | '//ex(split%strain)//' | '// &
        ex(split%dissipated)//' | '//ex(split%loss)//' | '//ex(-split%w_grav)//' | '//ex(-split%w_ext)//' | '// &
        ex(-split%balance)//' | '//ex(split%books - split%absorbed)//' |'
      print '(a)', '| '//trim(modes(k))//', share of absorbed | | | | 100 % | '// &
        fx(100*split%vibration/split%absorbed, 1)//' % | '//fx(100*split%strain/split%absorbed, 1)//' % | '// &
        fx(100*split%dissipated/split%absorbed, 1)//' % | '//fx(100*split%loss/split%absorbed, 1)//' % | '// &
        fx(-100*split%w_grav/split%absorbed, 1)//' % | '//fx(-100*split%w_ext/split%absorbed, 1)//' % | '// &
        fx(-100*split%balance/split%absorbed, 1)//' % | |'
    end do

    print '(a)', ''
    print '(a)', '| plate | alpha_max mm | t_alpha ms | duration ms | 2.9432 alpha_m/V ms | ratio | Hertz + gravity'// &
                 ' (own alpha_m) ms | ratio | hertz_contact_duration ms | ratio | 2 t_alpha / duration | v_out m/s | run s |'
    print '(a)', '|---|---|---|---|---|---|---|---|---|---|---|---|---|'
    do k = 1, 2
      associate (run => runs(k))
      alpha_m = value_of(run, 'alpha_max_mm')
      t_alpha = value_of(run, 't_alpha_max_ms')
      v_in = value_of(run, 'impact_velocity_m_s')
      duration = value_of(run, 'contact_duration_ms')
      hertz_own = hertz_duration_constant*alpha_m/v_in
      hertz_g = 1.0e3_dp*hertz_duration(v_in, 9.8_dp, 1.0e-3_dp*alpha_m)
      hertz_ref = value_of(run, 'hertz_contact_duration_ms')
      print '(a)', '| '//trim(modes(k))//' | '//fx(alpha_m, 4)//' | '//fx(t_alpha, 3)//' | '//fx(duration, 3)//' | '// &
        fx(hertz_own, 4)//' | '//fx(duration/hertz_own, 4)//' | '//fx(hertz_g, 4)//' | '// &
        fx(duration/hertz_g, 4)//' | '//fx(hertz_ref, 4)//' | '//fx(duration/hertz_ref, 4)//' | '// &
        fx(2*t_alpha/duration, 4)//' | '//fx(value_of(run, 'rebound_velocity_m_s'), 5)//' | '// &
        fx(run%seconds, 2)//' |'
      end associate
    end do

    do k = 1, 2
      tag = 'restitution_'//trim(modes(k))
      split = energy_split(runs(k))
      call check_text_contains(tag//'_stops_at_separation', summary_value(runs(k)%record, 'stop_reason'), &
                               'separation')
      ! Summary keys agree with their definitions (10 printed digits: rtol 1e-8).
      call check_close(tag//'_mass_kg_is_the_whole_body_mass', split%mass, split%body_mass, 1.0e-8_dp)
      call check_text_contains(tag//'_energy_basis_is_whole_body', summary_value(runs(k)%record, 'energy_basis'), &
                               'whole body')
      call check_close(tag//'_rebound_is_final_cm_velocity', split%v_out, split%v_cm, 1.0e-8_dp)
      call check_close(tag//'_e2_is_1_minus_absorbed_fraction', split%e**2, 1.0_dp - split%absorbed/split%input, &
                       1.0e-8_dp)
      ! The books close: the summary's 10 digits of M, V and absorbed and the
      ! cancellation in KE - 1/2 M v^2 (terms of size KE0) allow ~1e-9 KE0.
      call check_close(tag//'_books_close', split%books, split%absorbed, 0.0_dp, 1.0e-8_dp*split%ke0)
      ! No energy is created, and the deficit stays small (the split explains it).
      call check(tag//'_e_at_most_1', split%e <= 1.0_dp, 'e = '//fx(split%e, 8))
      call check(tag//'_e_above_0.99', split%e > 0.99_dp, 'e = '//fx(split%e, 8))
      ! For an elastic body the internal work (trapezoidal, exact for linear
      ! forces) equals the stored energy: dissipated_J is round-off, and
      ! Wilson-theta's algorithmic loss shows in balance_error_J instead.
      call check(tag//'_elastic_dissipated_is_roundoff', abs(split%dissipated) <= 1.0e-12_dp*split%ke0, &
                 'dissipated '//ex(split%dissipated)//' J')
      ! What the books cannot attribute (the balance error) is a small part of
      ! the deficit: 1 - e^2 is explained to 10 %.
      call check(tag//'_unexplained_below_10pc_of_absorbed', abs(split%balance) <= 0.1_dp*split%absorbed, &
                 '2 pi balance '//ex(split%balance)//' J, absorbed '//ex(split%absorbed)//' J')
      associate (run => runs(k))
      ! RELEASE=YES frees a node only when its reaction turns tensile: none
      ! during loading, and once unloading has begun the contact only shrinks.
      call chatter(run%t, run%n, value_of(run, 't_alpha_max_ms'), early, recaptured)
      call check(tag//'_no_release_before_alpha_max_no_recapture', early == 0 .and. recaptured == 0, &
                 integer_text(early)//' early releases, '//integer_text(recaptured)//' recaptures')
      alpha_m = value_of(run, 'alpha_max_mm')
      v_in = value_of(run, 'impact_velocity_m_s')
      duration = value_of(run, 'contact_duration_ms')
      ! Hertz's relation T = 2.9432 alpha_m / V with the run's own alpha_m holds
      ! for a force law F ~ alpha^(3/2) without gravity. Allowed: the duration is
      ! found at the first step after separation (0 .. +dt = 0.33 %); gravity
      ! shortens it by 0.43 % (the oscillator with g); the finite sphere's
      ! force-approach exponent, measured 1.49 .. 1.57 over the pulse, changes
      ! the constant 2 (2/(n+1)) B(1/(n+1), 1/2) by up to 0.8 %: 2 % in all.
      call check_close(tag//'_duration_vs_hertz_own_alpha', duration, hertz_duration_constant*alpha_m/v_in, 0.02_dp)
      call check_close(tag//'_duration_vs_hertz_gravity_own_alpha', duration, &
                       1.0e3_dp*hertz_duration(v_in, 9.8_dp, 1.0e-3_dp*alpha_m), 0.02_dp)
      end associate
    end do
  end subroutine test_restitution

  integer function index_of(run, name) result(k)
    type(run_t), intent(in) :: run
    character(*), intent(in) :: name
    integer :: i
    k = 0
    do i = 1, size(run%record%columns)
      if (trim(run%record%columns(i)) == name) k = i
    end do
  end function index_of

  ! ---------------------------------------------------------------- 3. Table 2

  subroutine test_table2()
    type(run_t) :: runs(3:4)
    real(dp) :: t_alpha(3:4), t_q(3:4), ring(3:4), resolution(3:4)
    integer :: level
    character(:), allocatable :: tag
    character(len=line_length), allocatable :: lines(:)

    print '(a)', ''
    print '(a)', '### 3. Viscoelastic sphere of Table 2 (K 13.5 MPa, G 3.91 MPa, beta 203 1/s, drop 5 cm, dt 1e-5)'
    do level = 3, 4
      lines = [character(len=line_length) :: 'ANALYSIS DYNAMIC', 'GEOMETRY AXISYMMETRIC', &
               'MATERIAL apple VISCOELASTIC K=13.5e6 RHO=757', 'PRONY G=3.91e6 BETA=203']
      call add(lines, 'MESH SPHERE R=0.0366 LEVEL='//integer_text(level))
      call add(lines, 'DROP HEIGHT=0.05')
      call add(lines, 'GRAVITY G=9.8')
      call add(lines, 'WILSON THETA=1.4')
      call add(lines, 'TIME DT=1e-5 TEND=4e-3')
      call add(lines, 'PLATE Z=0')
      runs(level) = run_case('table2_level'//integer_text(level), lines)
      if (.not. runs(level)%ok) return
      t_alpha(level) = value_of(runs(level), 't_alpha_max_ms')
      t_q(level) = value_of(runs(level), 't_q_max_ms')
      ring(level) = ring_interval(runs(level)%t, runs(level)%n, t_alpha(level))
    end do
    ! The resolution of t_alpha - t_q: the sampling (2 dt) plus its level 3 -> 4
    ! change, as for the apples of section 4. (It was the larger of 2 dt and
    ! the ring interval, the mean time between the last three ring arrivals
    ! before t_alpha: on the GRADE=2.5 grid 0.315 ms at level 3 and 0.285 ms
    ! at level 4 against leads of 0.367 and 0.337 ms. That interval measures
    ! where the largest contact radius falls among the node rings, not how
    ! well t_q is known: on the GRADE=4.5 grid level 3's last ring joins at
    ! 1.73 ms, 0.18 ms after the q peak (1.55 ms) and 0.16 ms before t_alpha,
    ! where the contact edge creeps, so the interval is 0.465 ms, and 0.210 ms
    ! at level 4. How well the lead is known, measured offline on the new
    ! grid: 0.338 ms (level 3), 0.387 (4), 0.377 (5) at dt = 1e-5, 0.348 and
    ! 0.347 (levels 3, 4) at 2e-5, 0.378 and 0.352 at 5e-6: it stays within
    ! 0.338 .. 0.387 ms, the spread the level 3 -> 4 change shows.)
    resolution = 2.0_dp*runs(3)%dt_ms + abs((t_alpha(4) - t_q(4)) - (t_alpha(3) - t_q(3)))
    print '(a)', ''
    print '(a)', 'Ring interval: mean time between the last three increases of n_contact before t_alpha.'// &
                 ' Resolution of t_alpha - t_q: 2 dt plus its level 3 -> 4 change.'
    print '(a)', ''
    print '(a)', '| source | alpha_max mm | t_alpha ms | q_max MPa | t_q ms | q_surface_max MPa | t_q_surface ms |'// &
                 ' force_max N | t_force ms | ring interval ms | t_alpha - t_q ms | resolution ms | Hertz alpha mm |'// &
                 ' Hertz q MPa | run s |'
    print '(a)', '|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|'
    print '(a)', '| paper (Table 2) | 1.34 | 1.80 | 1.17 | 1.60 | | | | | | 0.20 | | | | |'
    do level = 3, 4
      associate (run => runs(level))
      print '(a)', '| visco2d level '//integer_text(level)//' | '//fx(value_of(run, 'alpha_max_mm'), 4)//' | '// &
        fx(t_alpha(level), 3)//' | '//fx(value_of(run, 'q_max_MPa'), 4)//' | '//fx(t_q(level), 3)//' | '// &
        fx(value_of(run, 'q_surface_max_MPa'), 4)//' | '//fx(value_of(run, 't_q_surface_max_ms'), 3)//' | '// &
        fx(value_of(run, 'force_max_N'), 2)//' | '//fx(value_of(run, 't_force_max_ms'), 3)//' | '// &
        fx(ring(level), 3)//' | '//fx(t_alpha(level) - t_q(level), 3)//' | '//fx(resolution(level), 3)//' | '// &
        fx(value_of(run, 'hertz_alpha_max_mm'), 4)//' | '//fx(value_of(run, 'hertz_q_max_MPa'), 3)//' | '// &
        fx(run%seconds, 2)//' |'
      end associate
    end do
    do level = 3, 4
      tag = 'table2_level'//integer_text(level)
      associate (run => runs(level))
      ! The relaxing sphere unloads its pole before the centre stops: q leads
      ! alpha by more than the sampling (2 dt) and the level 3 -> 4 change.
      call check(tag//'_q_peaks_before_alpha_beyond_resolution', t_alpha(level) - t_q(level) > resolution(level), &
                 't_alpha - t_q = '//fx(t_alpha(level) - t_q(level), 3)//' ms, resolution '// &
                 fx(resolution(level), 3)//' ms')
      ! The q peak is smooth, not a ring arrival: where a ring joins within 2
      ! steps of it, q changes at that arrival by less than 0.1 % of q_max
      ! (near a smooth peak a step changes q by under 1e-4 q_max here: 7e-5 q_max
      ! the step before it; an arrival's jump reaches 15-17 % of q, section 5).
      ! On the contact grid at
      ! level 4 ring 18 joins at the peak step itself (1.55 ms), where q rises
      ! by 3.0e-5 MPa (2e-5 q_max) after +9.3e-5 MPa the step before, a plateau
      ! it does not shape; on the legacy grid no ring joined within 2 steps.
      ! The run went on past the peak, and the independent recovery (-sigma_z
      ! extrapolated to the pole) peaks at the same step (2 dt).
      print '(a)', tag//': largest q change at a ring arrival within 2 dt of t_q: '// &
        ex(ring_jump_near(run%t, run%n, run%q, t_q(level), 2*run%dt_ms))//' MPa'
      call check(tag//'_q_peak_not_at_a_ring_arrival', &
                 ring_jump_near(run%t, run%n, run%q, t_q(level), 2*run%dt_ms) < 1.0e-3_dp*maxval(run%q) .and. &
                 t_q(level) < value_of(run, 't_stop_ms') - 2*run%dt_ms)
      call check_close(tag//'_q_surface_peaks_with_q', value_of(run, 't_q_surface_max_ms'), t_q(level), 0.0_dp, &
                       2*run%dt_ms + 1.0e-9_dp)
      end associate
    end do
  end subroutine test_table2

  ! ---------------------------------------------------------------- 4. apples

  !> Table 3 apple (R 35 mm, rho 790) at 0.7 or 1.2 m/s (its own Prony set),
  !> STICK RELEASE=YES, run past both maxima (STOP AT=TEND).
  function apple_deck(level, slow) result(lines)
    integer, intent(in) :: level
    logical, intent(in) :: slow
    character(len=line_length), allocatable :: lines(:)
    lines = [character(len=line_length) :: 'ANALYSIS DYNAMIC', 'GEOMETRY AXISYMMETRIC']
    if (slow) then
      call add(lines, 'MATERIAL apple VISCOELASTIC K=1.756e6 RHO=790')
      call add(lines, 'PRONY G=0.636e6 BETA=0.000347')
      call add(lines, 'PRONY G=0.111e6 BETA=0.0409')
      call add(lines, 'PRONY G=0.208e6 BETA=1.121')
      call add(lines, 'PRONY G=0.099e6 BETA=35.26')
      call add(lines, 'INITIAL VZ=-0.7 AZ=-9.8')
      call add(lines, 'TIME DT=1e-5 TEND=3.8e-3')
    else
      call add(lines, 'MATERIAL apple VISCOELASTIC K=2.047e6 RHO=790')
      call add(lines, 'PRONY G=0.710e6 BETA=0.000380')
      call add(lines, 'PRONY G=0.134e6 BETA=0.0420')
      call add(lines, 'PRONY G=0.265e6 BETA=1.633')
      call add(lines, 'PRONY G=0.119e6 BETA=41.30')
      call add(lines, 'INITIAL VZ=-1.2 AZ=-9.8')
      call add(lines, 'TIME DT=1e-5 TEND=3.3e-3')
    end if
    call add(lines, 'MESH SPHERE R=0.035 LEVEL='//integer_text(level))
    call add(lines, 'GRAVITY G=9.8')
    call add(lines, 'WILSON THETA=1.4')
    call add(lines, 'PLATE Z=0 STICK RELEASE=YES')
    call add(lines, 'STOP AT=TEND')
  end function apple_deck

  subroutine test_apples()
    type(run_t) :: runs(2, 3:4)
    real(dp) :: t_alpha(2, 3:4), t_q(2, 3:4), ring(2, 3:4), t_end(2, 3:4), dt, resolution_alpha, resolution_q
    real(dp) :: lead(2, 3:4), lead_resolution(2)
    character(len=3), parameter :: speeds(2) = ['0.7', '1.2']
    integer :: level, k
    character(:), allocatable :: tag

    print '(a)', ''
    print '(a)', '### 4. Apples of Table 3 (R 35 mm, rho 790, STICK RELEASE=YES, dt 1e-5, run past both maxima)'
    do level = 3, 4
      do k = 1, 2
        runs(k, level) = run_case('apple_'//speeds(k)//'_level'//integer_text(level), apple_deck(level, k == 1))
        if (.not. runs(k, level)%ok) return
        t_alpha(k, level) = value_of(runs(k, level), 't_alpha_max_ms')
        t_q(k, level) = value_of(runs(k, level), 't_q_max_ms')
        lead(k, level) = t_alpha(k, level) - t_q(k, level)
        ring(k, level) = ring_interval(runs(k, level)%t, runs(k, level)%n, t_q(k, level))
        t_end(k, level) = value_of(runs(k, level), 't_stop_ms')
      end do
    end do
    dt = runs(1, 3)%dt_ms
    print '(a)', ''
    print '(a)', '| V m/s | level | alpha_max mm | t_alpha ms | q_max MPa | t_q ms | force_max N | t_force ms |'// &
                 ' ring interval before t_q ms | t_alpha - t_q ms | Hertz alpha mm | Hertz q MPa | run s |'
    print '(a)', '|---|---|---|---|---|---|---|---|---|---|---|---|---|'
    do level = 3, 4
      do k = 1, 2
        associate (run => runs(k, level))
        print '(a)', '| '//speeds(k)//' | '//integer_text(level)//' | '//fx(value_of(run, 'alpha_max_mm'), 4)//' | '// &
          fx(t_alpha(k, level), 3)//' | '//fx(value_of(run, 'q_max_MPa'), 4)//' | '//fx(t_q(k, level), 3)//' | '// &
          fx(value_of(run, 'force_max_N'), 2)//' | '//fx(value_of(run, 't_force_max_ms'), 3)//' | '// &
          fx(ring(k, level), 3)//' | '//fx(lead(k, level), 3)//' | '//fx(value_of(run, 'hertz_alpha_max_mm'), 4)// &
          ' | '//fx(value_of(run, 'hertz_q_max_MPa'), 4)//' | '//fx(run%seconds, 2)//' |'
        end associate
      end do
    end do
    ! Resolution of a peak time: 2 dt (sampling) plus its change from level 3 to
    ! level 4 at either speed (the mesh's share).
    resolution_alpha = 2*dt + maxval(abs(t_alpha(:, 4) - t_alpha(:, 3)))
    resolution_q = 2*dt + maxval(abs(t_q(:, 4) - t_q(:, 3)))
    lead_resolution = 2*dt + abs(lead(:, 4) - lead(:, 3))
    print '(a)', ''
    print '(a)', 'Resolution: 2 dt plus the level 3 -> 4 change. Reference: the elastic sphere of section 1 (Hertz:'// &
                 ' alpha and q peak together) gives t_alpha - t_q = '//fx(elastic_lead(3), 3)//' ms (level 3), '// &
                 fx(elastic_lead(4), 3)//' ms (level 4).'
    print '(a)', ''
    print '(a)', '| quantity (level 4) | 0.7 m/s | 1.2 m/s | paper | resolution ms |'
    print '(a)', '|---|---|---|---|---|'
    print '(a)', '| t_alpha ms | '//fx(t_alpha(1, 4), 3)//' | '//fx(t_alpha(2, 4), 3)//' | | '// &
                 fx(resolution_alpha, 3)//' |'
    print '(a)', '| t_q ms | '//fx(t_q(1, 4), 3)//' | '//fx(t_q(2, 4), 3)//' | | '//fx(resolution_q, 3)//' |'
    print '(a)', '| t_alpha - t_q ms | '//fx(lead(1, 4), 3)//' (+-'//fx(lead_resolution(1), 3)// &
                 ') | '//fx(lead(2, 4), 3)//' (+-'//fx(lead_resolution(2), 3)//') | ~0.2 / ~0 | |'
    print '(a)', '| ring interval before t_q ms | '//fx(ring(1, 4), 3)//' | '//fx(ring(2, 4), 3)//' | | |'
    do level = 3, 4
      do k = 1, 2
        tag = 'apple_'//speeds(k)//'_level'//integer_text(level)
        ! Both maxima are interior: the run went on at least 0.2 ms past them.
        call check(tag//'_maxima_inside_run', max(t_alpha(k, level), t_q(k, level)) < t_end(k, level) - 0.2_dp, &
                   't_alpha '//fx(t_alpha(k, level), 3)//', t_q '//fx(t_q(k, level), 3)//', end '// &
                   fx(t_end(k, level), 3))
      end do
    end do
    call check('apples_alpha_sooner_at_1.2', t_alpha(1, 4) - t_alpha(2, 4) > resolution_alpha, &
               fx(t_alpha(1, 4), 3)//' vs '//fx(t_alpha(2, 4), 3)//' ms')
    call check('apples_q_sooner_at_1.2', t_q(1, 4) - t_q(2, 4) > resolution_q, &
               fx(t_q(1, 4), 3)//' vs '//fx(t_q(2, 4), 3)//' ms')
  end subroutine test_apples

  ! ---------------------------------------------------------------- 5. nu = 0.4999

  subroutine test_incompressible()
    character(len=8), parameter :: forms(3) = ['BBAR    ', 'BBAR    ', 'STANDARD']
    character(len=6), parameter :: nus(3) = ['0.49  ', '0.4999', '0.4999']
    type(run_t) :: runs(3), release(2)
    integer :: early(2), recaptured(2)
    real(dp) :: alpha(3), t_alpha(3), f_fit_max(3), spike(3), jump(3), ring, mavg(3), t_mavg, roughness(3)
    real(dp) :: hertz_ratio, force_scaled, q_at_alpha(3), q_jump(3), decay(3)
    real(dp), allocatable :: fit(:), alpha_fit(:), q_surface(:)
    integer :: k, i
    character(:), allocatable :: tag

    print '(a)', ''
    print '(a)', '### 5. Nearly incompressible sphere (E 18.11 MPa, level 3, dt 1e-5, STICK): BBAR vs STANDARD'
    print '(a)', ''
    print '(a)', '| formulation | nu | alpha_max mm | t_alpha ms | t_stop ms | stop | t_paper ms | force_max N |'// &
                 ' t_force ms | F fit peak N | moving-avg peak N | max abs(F - fit) / fit peak | max jump / fit peak |'// &
                 ' spike decay per step | q_max MPa | t_q ms | q at t_alpha MPa | max q jump / q(t_alpha) |'// &
                 ' alpha roughness |'
    print '(a)', '|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|'
    do k = 1, 3
      tag = 'nu'//trim(nus(k))//'_'//trim(forms(k))
      runs(k) = run_case(tag, table1_deck(3, 1.0e-5_dp, 4.0e-3_dp, 'PLATE Z=0', poisson=trim(nus(k)), &
                                          formulation=trim(forms(k))))
      if (.not. runs(k)%ok) return
      associate (run => runs(k))
      alpha(k) = value_of(run, 'alpha_max_mm')
      t_alpha(k) = value_of(run, 't_alpha_max_ms')
      ! Smooth estimates: a least-squares quartic through the force history
      ! (the pulse is ~sin^(3/2): a quartic follows it to ~1 %), and the peak of
      ! the moving average over one ring-arrival interval.
      fit = poly_fit(run%t, run%force, 4)
      f_fit_max(k) = maxval(fit)
      spike(k) = maxval(abs(run%force - fit))/f_fit_max(k)
      jump(k) = maxval(abs(run%force(2:) - run%force(:size(run%force) - 1)))/f_fit_max(k)
      ring = ring_interval(run%t, run%n, t_alpha(k))
      mavg(k) = -1.0_dp
      if (ring > 0.0_dp) call moving_average_peak(run%t, run%force, ring, mavg(k), t_mavg)
      ! alpha's roughness: max deviation from a least-squares sextic, / alpha_m.
      alpha_fit = poly_fit(run%t, run%alpha, 6)
      roughness(k) = maxval(abs(run%alpha - alpha_fit))/alpha(k)
      i = minloc(abs(run%t - t_alpha(k)), dim=1)
      q_at_alpha(k) = run%q(i)
      q_jump(k) = maxval(abs(run%q(2:) - run%q(:size(run%q) - 1)))/q_at_alpha(k)
      ! Decay per step of the largest force spike: (r_{i+6}/r_i)^(1/6) of the
      ! residual r = F - fit, signed by r_{i+1}/r_i (negative: period-2 mode).
      i = maxloc(abs(run%force - fit), dim=1)
      decay(k) = 0.0_dp
      if (i + 6 <= size(fit)) decay(k) = sign(abs((run%force(i + 6) - fit(i + 6))/(run%force(i) - fit(i)))**(1.0_dp/6), &
                                             (run%force(i + 1) - fit(i + 1))/(run%force(i) - fit(i)))
      print '(a)', '| '//trim(forms(k))//' | '//trim(nus(k))//' | '//fx(alpha(k), 4)//' | '//fx(t_alpha(k), 3)// &
        ' | '//fx(value_of(run, 't_stop_ms'), 3)//' | '//summary_value(run%record, 'stop_reason')//' | '// &
        fx(value_of(run, 't_paper_criterion_ms'), 3)//' | '//fx(value_of(run, 'force_max_N'), 1)//' | '// &
        fx(value_of(run, 't_force_max_ms'), 3)//' | '//fx(f_fit_max(k), 1)//' | '//fx(mavg(k), 1)//' | '// &
        fx(spike(k), 3)//' | '//fx(jump(k), 3)//' | '//fx(decay(k), 3)//' | '//fx(value_of(run, 'q_max_MPa'), 3)// &
        ' | '//fx(value_of(run, 't_q_max_ms'), 3)//' | '//fx(q_at_alpha(k), 3)//' | '//fx(q_jump(k), 3)//' | '// &
        ex(roughness(k))//' |'
      end associate
    end do

    ! Hertz: alpha_m ~ ((1 - nu^2)/E)^(2/5), F_m ~ (E/(1 - nu^2))^(2/5) at the same M and V.
    hertz_ratio = ((1.0_dp - 0.4999_dp**2)/(1.0_dp - 0.49_dp**2))**0.4_dp
    force_scaled = f_fit_max(1)/hertz_ratio
    print '(a)', ''
    print '(a)', '| comparison | value |'
    print '(a)', '|---|---|'
    print '(a)', '| alpha(BBAR 0.4999) / alpha(BBAR 0.49) | '//fx(alpha(2)/alpha(1), 5)//' (Hertz '// &
                 fx(hertz_ratio, 5)//') |'
    print '(a)', '| alpha(STANDARD 0.4999) / alpha(BBAR 0.4999) | '//fx(alpha(3)/alpha(2), 4)//' |'
    print '(a)', '| force_max_N(BBAR 0.4999) / smooth peak (fit) | '// &
                 fx(value_of(runs(2), 'force_max_N')/f_fit_max(2), 3)//' |'
    print '(a)', '| smooth peak (fit) BBAR 0.4999 / Hertz-scaled BBAR 0.49 fit peak | '// &
                 fx(f_fit_max(2)/force_scaled, 4)//' |'
    print '(a)', '| q_max_MPa(BBAR 0.4999) / q at t_alpha | '//fx(value_of(runs(2), 'q_max_MPa')/q_at_alpha(2), 2)//' |'

    ! The same impacts with RELEASE=YES to separation: a node is freed when its
    ! reaction (at t + dt) turns tensile, so the spikes can free it.
    print '(a)', ''
    print '(a)', 'With PLATE Z=0 STICK RELEASE=YES, STOP AT=SEPARATION (nu = 0.219: section 2, no early release):'
    print '(a)', ''
    print '(a)', '| formulation | nu | e | duration ms | 2.9432 alpha_m/V ms | releases before t_alpha |'// &
                 ' recaptures after first release | force_max N | q_max MPa |'
    print '(a)', '|---|---|---|---|---|---|---|---|---|'
    do k = 1, 2
      release(k) = run_case('nu'//trim(nus(k))//'_'//trim(forms(k))//'_release', table1_deck(3, 1.0e-5_dp, 6.0e-3_dp, &
                            'PLATE Z=0 STICK RELEASE=YES', 'STOP AT=SEPARATION', poisson=trim(nus(k)), &
                            formulation=trim(forms(k))))
      if (.not. release(k)%ok) return
      call chatter(release(k)%t, release(k)%n, value_of(release(k), 't_alpha_max_ms'), early(k), recaptured(k))
      print '(a)', '| '//trim(forms(k))//' | '//trim(nus(k))//' | '// &
        fx(value_of(release(k), 'coefficient_of_restitution'), 5)//' | '// &
        fx(value_of(release(k), 'contact_duration_ms'), 3)//' | '//fx(hertz_duration_constant* &
        value_of(release(k), 'alpha_max_mm')/value_of(release(k), 'impact_velocity_m_s'), 3)//' | '// &
        integer_text(early(k))//' | '//integer_text(recaptured(k))//' | '//fx(value_of(release(k), 'force_max_N'), 1)//' | '// &
        fx(value_of(release(k), 'q_max_MPa'), 2)//' |'
    end do
    ! Through rebound: an elastic body cannot come back faster than it came
    ! (e <= 1), and the contact lasts Hertz's 2.9432 alpha_m/V to 2 % (the
    ! sources of the 2 % as in test_restitution). At nu = 0.49 no node lets
    ! go before maximum deformation; at 0.4999 with STICK a few edge nodes
    ! may (tension at the edge of a bonded, nearly incompressible contact):
    ! they are printed, and e and the duration must still hold.
    do k = 1, 2
      call check('release_bbar_nu'//trim(nus(k))//'_restitution_at_most_1', &
                 value_of(release(k), 'coefficient_of_restitution') <= 1.0_dp, &
                 'e = '//fx(value_of(release(k), 'coefficient_of_restitution'), 6))
      call check_close('release_bbar_nu'//trim(nus(k))//'_duration_hertz', value_of(release(k), 'contact_duration_ms'), &
                       hertz_duration_constant*value_of(release(k), 'alpha_max_mm')/ &
                       value_of(release(k), 'impact_velocity_m_s'), 0.02_dp)
      if (early(k) > 0) print '(a)', 'NOTE RELEASE=YES, BBAR nu = '//trim(nus(k))//': '//integer_text(early(k))// &
        ' releases before maximum deformation and '//integer_text(recaptured(k))//' recaptures'
    end do
    call check('release_bbar_nu'//trim(nus(1))//'_no_early_release', early(1) == 0, integer_text(early(1))//' early releases')

    ! BBAR does not lock: alpha_m follows Hertz's (1 - nu^2) scaling from
    ! nu = 0.49 to 0.4999 (-0.52 %) to 0.5 % (measured 0.05 %; the level-3
    ! mesh error of alpha_m itself is 0.02 % on the contact grid, section 1,
    ! and was ~0.5 % on the legacy grid, where the bound was 1 %).
    call check_close('nu0.4999_bbar_alpha_follows_hertz_scaling', alpha(2)/alpha(1), hertz_ratio, 0.005_dp)
    ! STANDARD locks: much stiffer, alpha_m at least 10 % below BBAR's (measured
    ! at levels 2, 3, 4 on the contact grid: -26.8, -13.3, -6.5 %, halving per
    ! level where BBAR's alpha_m changes by 0.5 and 0.08 %: an error of another
    ! order; on the legacy grid, whose distorted pole elements lock harder,
    ! -50.8, -41.0, -28.3 %, and the bound was 20 %).
    call check('nu0.4999_standard_locks', alpha(3) < 0.9_dp*alpha(2), 'ratio '//fx(alpha(3)/alpha(2), 4))
    ! The run stopped at the true maximum deformation, not early on a spike:
    ! stop reason, t_stop one step after t_alpha, and t_alpha as for nu = 0.49 (2 dt).
    call check_text_contains('nu0.4999_bbar_stop_reason', summary_value(runs(2)%record, 'stop_reason'), &
                             'maximum deformation')
    call check_close('nu0.4999_bbar_stops_just_after_alpha_max', value_of(runs(2), 't_stop_ms'), t_alpha(2), &
                     0.0_dp, 2*runs(2)%dt_ms + 1.0e-9_dp)
    call check_close('nu0.4999_bbar_t_alpha_as_nu0.49', t_alpha(2), t_alpha(1), 0.0_dp, 2*runs(2)%dt_ms + 1.0e-9_dp)
    ! alpha (the centre of mass, an integral quantity) stays smooth: its
    ! deviation from a smooth fit is no more than twice that of nu = 0.49.
    call check('nu0.4999_bbar_alpha_smooth', roughness(2) <= 2.0_dp*roughness(1), &
               ex(roughness(2))//' vs '//ex(roughness(1)))
    ! The smooth force (fit) follows Hertz's scaling of the nu = 0.49 force to
    ! 3 % (the fit's own error ~1 %, the mesh's ~1 %, section 1).
    call check_close('nu0.4999_bbar_smooth_force_follows_hertz_scaling', f_fit_max(2), force_scaled, 0.03_dp)
    ! The reported maxima are not spikes: force_max_N is the smooth peak to
    ! 3 % and q_max_MPa is q at maximum deformation's time to 3 % (the
    ! reactions are taken at t + theta dt, where Wilson-theta holds
    ! equilibrium; at t + dt they carried period-2 spikes of 5x the force).
    call check_close('nu0.4999_bbar_force_max_is_smooth_peak', value_of(runs(2), 'force_max_N'), f_fit_max(2), 0.03_dp)
    call check_close('nu0.4999_bbar_q_max_near_alpha_max', value_of(runs(2), 'q_max_MPa'), q_at_alpha(2), 0.03_dp)
    ! The surface stress -sigma_z at the pole (q_surface) is taken at t + theta dt
    ! too: at t + dt it carried the stiff dilatational modes a touching node
    ! excites (90.7 MPa at the first step, then -26, +24, -18 ... MPa against
    ! q = 2.5 MPa). Now it peaks with alpha (2 dt), never pulls (>= -5 % of q_max),
    ! and reads q_max to 5 % (the Gauss-point extrapolation at the pole reads
    ! 3 % below the reaction projection on the contact grid: 0.974 and 0.970
    ! here, 0.971 at nu = 0.219 in section 1's level-3 run; on the legacy
    ! grid 4-8 % below, and the bound was 10 %).
    do k = 1, 2
      tag = 'nu'//trim(nus(k))//'_bbar_q_surface'
      associate (run => runs(k))
      q_surface = history_column(run%record, 'q_surface_MPa')
      print '(a)', 'BBAR nu = '//trim(nus(k))//': q_surface_max_MPa '//fx(value_of(run, 'q_surface_max_MPa'), 4)// &
        ' at '//fx(value_of(run, 't_q_surface_max_ms'), 3)//' ms, q_max_MPa '//fx(value_of(run, 'q_max_MPa'), 4)// &
        ', smallest q_surface '//fx(minval(q_surface), 4)//' MPa'
      call check_close(tag//'_max_at_alpha_max', value_of(run, 't_q_surface_max_ms'), t_alpha(k), 0.0_dp, &
                       2*run%dt_ms + 1.0e-9_dp)
      call check_close(tag//'_max_reads_q_max', value_of(run, 'q_surface_max_MPa'), value_of(run, 'q_max_MPa'), 0.05_dp)
      call check(tag//'_never_tensile', minval(q_surface) >= -0.05_dp*value_of(run, 'q_max_MPa'), &
                 fx(minval(q_surface), 4))
      end associate
    end do
  end subroutine test_incompressible
end program test_contact_dynamic
