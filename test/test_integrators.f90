!> Verification of the time integrators of the INTEGRATOR card (WILSON, NEWMARK,
!> HHT, GENERALIZED_ALPHA, BATHE) on a single degree of freedom, against each
!> method's amplification matrix A written here from the textbook definitions,
!> independently of the solver:
!>   Wilson-theta        Bathe and Wilson (linear acceleration over theta dt, then
!>                       interpolated back to dt);
!>   Newmark, HHT-alpha, generalized-alpha
!>                       Chung and Hulbert (1993): (1 - a_m) a_{n+1} + a_m a_n +
!>                       omega^2 ((1 - a_f) u_{n+1} + a_f u_n) = 0 with the Newmark
!>                       updates (HHT: a_m = 0, a_f = alpha, gamma = 1/2 + alpha,
!>                       beta = (1 + alpha)^2/4; generalized-alpha: a_m = (2 rho - 1)/
!>                       (rho + 1), a_f = rho/(rho + 1), gamma = 1/2 - a_m + a_f,
!>                       beta = (1 - a_m + a_f)^2/4);
!>   Bathe               Bathe and Baig (2005): the trapezoidal rule over dt/2, then
!>                       the 3-point backward Euler formula over the whole step.
!> The single degree of freedom is one plane-strain element with every
!> component fixed except u_z of node 3; omega^2 = k/m with k the diagonal
!> entry of the assembled stiffness and m the lumped mass of that equation
!> (the base's assemble_stiffness and lumped_mass, cross-checked by a static
!> run). Started with INITIAL VZ=v0 (a_0 = 0 from equilibrium), the program's
!> history must be A^n x0, x0 = (0, v0, 0). Checked:
!>   (a) u_n and v_n of the run = A^n x0 at dt/T = 0.1, 1 and 10;
!>   (b) the spectral radius at Omega = omega dt -> infinity against the closed
!>       forms (trapezoidal 1, HHT (1 - alpha)/(1 + alpha), generalized-alpha
!>       rho_inf, Bathe 0, Wilson the radius of A's limit matrix);
!>   (c) the period error and damping ratio at dt/T = 0.1 from A's eigenvalues,
!>       against the closed forms of the trapezoidal and linear-acceleration rules
!>       and against the period (zero crossings) and decay (Casoratian) measured
!>       from the program's history;
!>   (d) stability limits: Newmark beta = 1/6, gamma = 1/2 stable just below
!>       Omega = 2 sqrt(3), and the run stops with the instability error just
!>       above; Wilson theta = 1.0 (the same method) and 1.2 only conditionally
!>       stable (rho > 1 at large Omega).
!> Quadruple precision for the analytic side; tolerances explained where used.
program test_integrators
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, error_text
  use visco2d_deck, only: deck_t, read_deck
  use visco2d_banded, only: band_matrix_t
  use visco2d_assembly, only: assemble_stiffness, lumped_mass, node_dof, support_mask
  use visco2d_record, only: record_t
  use visco2d_driver, only: run_deck
  use visco2d_strings, only: integer_text
  use visco2d_testing, only: check, check_close, test_summary, write_deck, history_index, exact_text
  use visco2d_spectrum, only: qp, pi_qp, spectrum_t, spectrum_of, cubic
  implicit none

  character(*), parameter :: folder = 'build/test-tmp/integrators'

  ! The element: a square plane-strain block; only u_z of node 3 is free.
  real(dp), parameter :: side = 0.01_dp
  real(dp), parameter :: block_young = 1.0e6_dp, block_poisson = 0.25_dp, block_density = 1000.0_dp
  real(dp), parameter :: start_velocity = 0.1_dp
  !> The solver's energy-growth guard stops a run whose kinetic + internal
  !> energy exceeds 100 times the energy put in (energy_growth_limit of the
  !> dynamic solver, widened there for Wilson-theta's first-step overshoot).
  real(qp), parameter :: growth_guard = 100.0_qp

  integer, parameter :: kind_wilson = 1, kind_alpha = 2, kind_bathe = 3

  !> One integrator: its card and its textbook coefficients.
  type :: scheme_t
    character(len=24) :: name = ''
    character(len=80) :: card = ''
    integer :: kind = kind_alpha
    real(qp) :: theta = 1.0_qp, beta = 0.25_qp, gamma = 0.5_qp, alpha_m = 0.0_qp, alpha_f = 0.0_qp
    real(qp) :: radius_infinity = 1.0_qp      !< the closed-form spectral radius at Omega -> infinity
  end type scheme_t


  type(scheme_t), allocatable :: schemes(:)
  real(qp) :: omega2
  integer :: k

  call execute_command_line('mkdir -p '//folder)
  schemes = [wilson(1.4_qp), newmark(0.25_qp, 0.5_qp), hht(0.05_qp), generalized_alpha(0.8_qp), bathe()]
  omega2 = single_dof_omega2()
  call test_closed_forms()
  do k = 1, size(schemes)
    call test_limit_radius(schemes(k))
    call test_history(schemes(k), 0.1_dp, 1000, .true.)
    call test_history(schemes(k), 1.0_dp, 200, .false.)
    call test_history(schemes(k), 10.0_dp, 100, .false.)
  end do
  call test_stability_limits()
  call test_summary('test_integrators')

contains

  ! ------------------------------------------------------------ the schemes

  type(scheme_t) function wilson(theta) result(s)
    real(qp), intent(in) :: theta
    s%name = 'WILSON theta='//trim(qtoa_short(theta))
    s%card = 'INTEGRATOR WILSON THETA='//trim(qtoa_short(theta))
    s%kind = kind_wilson
    s%theta = theta
    s%beta = 1.0_qp/6.0_qp
    s%radius_infinity = -1.0_qp             ! no simple closed form: the limit matrix (test_limit_radius)
  end function wilson

  type(scheme_t) function newmark(beta, gamma) result(s)
    real(qp), intent(in) :: beta, gamma
    s%name = 'NEWMARK beta='//trim(qtoa_short(beta))
    s%card = 'INTEGRATOR NEWMARK BETA='//exact_text(real(beta, dp))//' GAMMA='//exact_text(real(gamma, dp))
    s%beta = beta
    s%gamma = gamma
    s%radius_infinity = 1.0_qp              ! the trapezoidal rule keeps every amplitude
  end function newmark

  type(scheme_t) function hht(alpha) result(s)
    real(qp), intent(in) :: alpha
    s%name = 'HHT alpha='//trim(qtoa_short(alpha))
    s%card = 'INTEGRATOR HHT ALPHA='//trim(qtoa_short(alpha))
    s%alpha_f = alpha
    s%gamma = 0.5_qp + alpha
    s%beta = (1.0_qp + alpha)**2/4.0_qp
    s%radius_infinity = (1.0_qp - alpha)/(1.0_qp + alpha)   ! Hilber, Hughes and Taylor 1977
  end function hht

  type(scheme_t) function generalized_alpha(rho) result(s)
    real(qp), intent(in) :: rho
    s%name = 'GENERALIZED_ALPHA rho_inf='//trim(qtoa_short(rho))
    s%card = 'INTEGRATOR GENERALIZED_ALPHA RHO_INF='//trim(qtoa_short(rho))
    s%alpha_m = (2.0_qp*rho - 1.0_qp)/(rho + 1.0_qp)
    s%alpha_f = rho/(rho + 1.0_qp)
    s%gamma = 0.5_qp - s%alpha_m + s%alpha_f
    s%beta = (1.0_qp - s%alpha_m + s%alpha_f)**2/4.0_qp
    s%radius_infinity = rho                  ! by construction (Chung and Hulbert 1993)
  end function generalized_alpha

  type(scheme_t) function bathe() result(s)
    s%name = 'BATHE'
    s%card = 'INTEGRATOR BATHE'
    s%kind = kind_bathe
    s%radius_infinity = 0.0_qp               ! Bathe and Baig 2005: L-stable
  end function bathe

  !> One step of u'' + w2 u = 0 from x = (u, v, a) over h, each method's textbook form.
  recursive function scheme_step(s, x, w2, h) result(next)
    type(scheme_t), intent(in) :: s
    real(qp), intent(in) :: x(3), w2, h
    real(qp) :: next(3)
    real(qp) :: tau, u_tau, a_tau, a1, predictor, half(3), u1, v1
    select case (s%kind)
    case (kind_wilson)
      tau = s%theta*h
      u_tau = (6.0_qp/tau**2*x(1) + 6.0_qp/tau*x(2) + 2.0_qp*x(3))/(w2 + 6.0_qp/tau**2)
      a_tau = 6.0_qp/tau**2*(u_tau - x(1)) - 6.0_qp/tau*x(2) - 2.0_qp*x(3)
      a1 = x(3) + (a_tau - x(3))/s%theta
      next = [x(1) + h*x(2) + h**2/6.0_qp*(2.0_qp*x(3) + a1), x(2) + h/2.0_qp*(x(3) + a1), a1]
    case (kind_alpha)
      predictor = x(1) + h*x(2) + h**2*(0.5_qp - s%beta)*x(3)
      a1 = -(s%alpha_m*x(3) + w2*((1.0_qp - s%alpha_f)*predictor + s%alpha_f*x(1))) / &
           ((1.0_qp - s%alpha_m) + w2*(1.0_qp - s%alpha_f)*s%beta*h**2)
      next = [predictor + s%beta*h**2*a1, x(2) + h*((1.0_qp - s%gamma)*x(3) + s%gamma*a1), a1]
    case (kind_bathe)
      half = scheme_step(newmark(0.25_qp, 0.5_qp), x, w2, h/2.0_qp)
      ! v1 = (u - 4 u_half + 3 u1)/h, a1 = (v - 4 v_half + 3 v1)/h, a1 + w2 u1 = 0
      u1 = -((x(2) - 4.0_qp*half(2))/h + 3.0_qp*(x(1) - 4.0_qp*half(1))/h**2)/(9.0_qp/h**2 + w2)
      v1 = (x(1) - 4.0_qp*half(1) + 3.0_qp*u1)/h
      next = [u1, v1, (x(2) - 4.0_qp*half(2) + 3.0_qp*v1)/h]
    end select
  end function scheme_step

  !> A: x_{n+1} = A x_n, column j = the step of unit state j.
  function amplification(s, w2, h) result(a)
    type(scheme_t), intent(in) :: s
    real(qp), intent(in) :: w2, h
    real(qp) :: a(3, 3)
    real(qp) :: unit(3)
    integer :: j
    do j = 1, 3
      unit = 0.0_qp
      unit(j) = 1.0_qp
      a(:, j) = scheme_step(s, unit, w2, h)
    end do
  end function amplification

  !> The spectrum at Omega = omega dt (omega = 1), with A scaled to the state
  !> (u, h v, h^2 a) (a similarity: the same eigenvalues, entries of order 1).
  function spectrum_at(s, big_omega) result(spectrum)
    type(scheme_t), intent(in) :: s
    real(qp), intent(in) :: big_omega
    type(spectrum_t) :: spectrum
    real(qp) :: a(3, 3), scale(3)
    integer :: i, j
    a = amplification(s, 1.0_qp, big_omega)
    scale = [1.0_qp, big_omega, big_omega**2]
    do j = 1, 3
      do i = 1, 3
        a(i, j) = a(i, j)*scale(i)/scale(j)
      end do
    end do
    spectrum = spectrum_of(a)
  end function spectrum_at

  real(qp) function radius_at(s, big_omega) result(radius)
    type(scheme_t), intent(in) :: s
    real(qp), intent(in) :: big_omega
    type(spectrum_t) :: spectrum
    spectrum = spectrum_at(s, big_omega)
    radius = spectrum%radius
  end function radius_at

  real(qp) function phase_at(s, big_omega) result(phase)
    type(scheme_t), intent(in) :: s
    real(qp), intent(in) :: big_omega
    type(spectrum_t) :: spectrum
    spectrum = spectrum_at(s, big_omega)
    phase = spectrum%phase
  end function phase_at


  function qtoa(value) result(text)
    real(qp), intent(in) :: value
    character(len=24) :: text
    write(text, '(es12.4)') real(value, dp)
    text = adjustl(text)
  end function qtoa

  !> A name as a file name: letters and digits kept, the rest '_'.
  function file_tag(name) result(tag)
    character(*), intent(in) :: name
    character(:), allocatable :: tag
    integer :: j
    tag = trim(name)
    do j = 1, len(tag)
      if (.not. (verify(tag(j:j), 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789') == 0)) tag(j:j) = '_'
    end do
  end function file_tag

  !> A short decimal for names and cards (up to 6 digits, trailing zeros cut).
  function qtoa_short(value) result(text)
    real(qp), intent(in) :: value
    character(len=24) :: text
    integer :: last
    write(text, '(f12.6)') real(value, dp)
    text = adjustl(text)
    last = len_trim(text)
    do while (last > 1 .and. text(last:last) == '0')
      last = last - 1
    end do
    if (text(last:last) == '.') last = last - 1
    text = text(1:last)
  end function qtoa_short

  ! ------------------------------------------------------------ the single degree of freedom

  !> The element's cards; `extra` adds the analysis-specific ones.
  function element_lines(analysis, extra) result(lines)
    character(*), intent(in) :: analysis
    character(*), intent(in) :: extra(:)
    character(len=120), allocatable :: lines(:)
    character(len=120) :: base(13)
    base(1) = 'TITLE single degree of freedom: u_z of node 3'
    base(2) = 'ANALYSIS '//analysis
    base(3) = 'GEOMETRY PLANESTRAIN'
    base(4) = 'MATERIAL block ELASTIC E='//exact_text(block_young)//' NU='//exact_text(block_poisson)// &
              ' RHO='//exact_text(block_density)
    base(5) = 'NODE 1 0 0'
    base(6) = 'NODE 2 '//exact_text(side)//' 0'
    base(7) = 'NODE 3 '//exact_text(side)//' '//exact_text(side)
    base(8) = 'NODE 4 0 '//exact_text(side)
    base(9) = 'ELEMENT 1 1 2 3 4'
    base(10) = 'FIX 1 RZ'
    base(11) = 'FIX 2 RZ'
    base(12) = 'FIX 3 R'
    base(13) = 'FIX 4 RZ'
    allocate(lines(size(base) + size(extra) + 1))
    lines(1:size(base)) = base
    lines(size(base) + 1:size(base) + size(extra)) = extra
    lines(size(lines)) = 'END'
  end function element_lines

  !> omega^2 = k/m: k the diagonal entry of the assembled stiffness at the one
  !> free equation, m its lumped mass. Cross-checks: exactly one free equation;
  !> m = rho side^2/4 (a square's corner share); a static run under a force F
  !> moves the node by F/k (one equation: one division, 1e-14 relative).
  real(qp) function single_dof_omega2() result(value)
    character(*), parameter :: path = folder//'/single_dof.inp'
    real(dp), parameter :: force = 1.0_dp
    type(deck_t) :: deck
    type(band_matrix_t) :: stiffness
    type(record_t) :: record
    type(error_t), allocatable :: error
    real(dp), allocatable :: mass(:), shear(:), bulk(:)
    logical, allocatable :: fixed(:)
    real(dp) :: k_diagonal, m_node, u_static
    integer :: free, column
    character(len=120) :: extra(2)
    value = 1.0_qp
    extra(1) = 'FORCE 3 FZ='//exact_text(force)
    extra(2) = 'PROBE free NODE=3'
    call write_deck(path, element_lines('STATIC', extra))
    call read_deck(path, deck, error)
    if (allocated(error)) then
      call check('single dof: deck reads', .false., error_text(error)); return
    end if
    fixed = support_mask(deck%mesh, deck%settings, deck%loads)
    free = node_dof(deck%mesh, 3, 2)
    call check('single dof: one free equation, u_z of node 3', count(.not. fixed) == 1 .and. .not. fixed(free))
    allocate(shear(deck%mesh%nelem), bulk(deck%mesh%nelem))
    shear = deck%materials(1)%shear
    bulk = deck%materials(1)%bulk
    call assemble_stiffness(deck%mesh, deck%settings, shear, bulk, stiffness)
    k_diagonal = stiffness%ab(1, free)
    mass = lumped_mass(deck%mesh, deck%settings, deck%materials)
    m_node = mass(free)
    call check_close('single dof: lumped mass = rho side^2/4', m_node, block_density*side**2/4.0_dp, 1.0e-14_dp)
    call run_deck(path, folder//'/out', record, error)
    if (allocated(error)) then
      call check('single dof: static run', .false., error_text(error)); return
    end if
    column = history_index(record, 'free_uz_m')
    call check('single dof: static history has the probe', column > 0 .and. record%nrow >= 1)
    if (column == 0) return
    u_static = record%history(column, record%nrow)
    call check_close('single dof: static u = F/k (k the diagonal stiffness entry)', u_static, force/k_diagonal, &
                     1.0e-12_dp)
    value = real(k_diagonal, qp)/real(m_node, qp)
    print '(a, es23.15, a, es23.15, a, es23.15)', 'single dof: k = ', k_diagonal, ' N/m, m = ', m_node, &
      ' kg, omega = ', sqrt(real(value, dp))
  end function single_dof_omega2

  !> The dynamic deck: v0 on the free equation, DT, steps, the integrator card.
  subroutine write_dynamic_deck(path, s, dt, steps)
    character(*), intent(in) :: path
    type(scheme_t), intent(in) :: s
    real(dp), intent(in) :: dt
    integer, intent(in) :: steps
    character(len=120) :: extra(5)
    extra(1) = 'INITIAL VZ='//exact_text(start_velocity)
    extra(2) = s%card
    extra(3) = 'TIME DT='//exact_text(dt)//' TEND='//exact_text(steps*dt)
    extra(4) = 'OUTPUT EVERY=1'
    extra(5) = 'PROBE free NODE=3'
    call write_deck(path, element_lines('DYNAMIC', extra))
  end subroutine write_dynamic_deck

  ! ------------------------------------------------------------ (a) and (c): the program's history

  !> Run the single dof with scheme s at dt/T = ratio for `steps` steps and
  !> compare u_n, v_n with A^n x0; with `measure`, also the period from the
  !> zero crossings and the decay from the Casoratian against A's eigenvalues.
  subroutine test_history(s, ratio, steps, measure)
    type(scheme_t), intent(in) :: s
    real(dp), intent(in) :: ratio
    integer, intent(in) :: steps
    logical, intent(in) :: measure
    character(len=16) :: tag
    character(:), allocatable :: name, path
    type(record_t) :: record
    type(error_t), allocatable :: error
    type(spectrum_t) :: spectrum
    real(qp) :: a(3, 3), x(3), h, energy_max
    real(qp), allocatable :: u_exact(:), v_exact(:)
    real(dp), allocatable :: u(:), v(:)
    real(dp) :: error_u, error_v, dt
    integer :: n, column_u, column_v
    write(tag, '(f8.2)') ratio
    name = trim(s%name)//' dt/T='//trim(adjustl(tag))
    path = folder//'/'//file_tag(s%name)//'_'//trim(adjustl(tag))//'.inp'
    dt = ratio*2.0_dp*acos(-1.0_dp)/sqrt(real(omega2, dp))
    call write_dynamic_deck(path, s, dt, steps)
    ! The analytic side uses the program's own DT (read back from the card text).
    h = real(dt, qp)
    a = amplification(s, omega2, h)
    spectrum = spectrum_of(a)
    allocate(u_exact(0:steps), v_exact(0:steps))
    x = [0.0_qp, real(start_velocity, qp), 0.0_qp]
    u_exact(0) = x(1)
    v_exact(0) = x(2)
    energy_max = 1.0_qp
    do n = 1, steps
      x = matmul(a, x)
      u_exact(n) = x(1)
      v_exact(n) = x(2)
      energy_max = max(energy_max, (x(2)**2 + omega2*x(1)**2)/real(start_velocity, qp)**2)
    end do

    call run_deck(path, folder//'/out', record, error)
    if (allocated(error)) then
      ! A stable run may be stopped by the energy guard only where the exact
      ! discrete solution's energy does exceed it (Wilson's first-step overshoot).
      call check(name//': runs, or stops only where the exact discrete energy exceeds the guard ('// &
        'max E_n/E_0 = '//trim(qtoa(energy_max))//')', energy_max > growth_guard, error_text(error))
      return
    end if
    column_u = history_index(record, 'free_uz_m')
    column_v = history_index(record, 'free_vz_m_s')
    call check(name//': history has every step', record%nrow == steps + 1 .and. column_u > 0 .and. column_v > 0, &
               'rows '//integer_text(record%nrow))
    if (record%nrow /= steps + 1 .or. column_u == 0 .or. column_v == 0) return
    u = record%history(column_u, 1:steps + 1)
    v = record%history(column_v, 1:steps + 1)
    ! (a) The program does the same linear recurrence in double precision: each
    ! step rounds the state to a few eps, carried (not amplified: rho <= 1), so
    ! the error after n steps is about 20 n eps of the amplitude (<= 5e-12 for
    ! n = 1000). 1e-9 of the amplitude leaves room for the different order of
    ! operations (residual form, stress increments), and still catches any
    ! coefficient that differs from the textbook method's in its 9th digit.
    error_u = real(maxval(abs(real(u, qp) - u_exact))/maxval(abs(u_exact)), dp)
    error_v = real(maxval(abs(real(v, qp) - v_exact))/maxval(abs(v_exact)), dp)
    print '(a, 2es10.2, a, f10.6)', name//': history error u, v (rel. to amplitude) ', error_u, error_v, &
      '  rho(A) ', real(spectrum%radius, dp)
    call check(name//': u_n = e1^T A^n x0 within 1e-9 of the amplitude', error_u <= 1.0e-9_dp, &
               'error '//trim(qtoa(real(error_u, qp))))
    call check(name//': v_n = e2^T A^n x0 within 1e-9 of the amplitude', error_v <= 1.0e-9_dp, &
               'error '//trim(qtoa(real(error_v, qp))))
    if (measure) call test_measured(name, s, spectrum, real(omega2, qp)**0.5_qp*h, u)
  end subroutine test_history

  !> (c) Period error and damping ratio of A at Omega against those measured
  !> from the history u: the period from its zero crossings, the decay r per
  !> step from the Casoratian D_n = u_{n+1}^2 - u_n u_{n+2}, which for
  !> u_n = C r^n cos(phi n + c) is C^2 r^(2n+2) sin^2(phi): D_m/D_l = r^(2(m - l))
  !> whatever the phase. Both after the spurious root has decayed to 1e-13.
  subroutine test_measured(name, s, spectrum, big_omega, u)
    character(*), intent(in) :: name
    type(scheme_t), intent(in) :: s
    type(spectrum_t), intent(in) :: spectrum
    real(qp), intent(in) :: big_omega
    real(dp), intent(in) :: u(:)
    real(qp) :: period_error, damping, period_measured, damping_measured, crossing_first, crossing_last
    real(qp) :: shift, bound, tolerance, r_measured, casoratian_first, casoratian_last
    integer :: first, last, n, crossings
    call check(name//': the principal roots are a complex pair', spectrum%oscillating)
    if (.not. spectrum%oscillating) return
    period_error = big_omega/spectrum%phase - 1.0_qp
    damping = -log(spectrum%modulus)/spectrum%phase
    first = 1
    if (abs(spectrum%root(3)) > 0.0_qp) first = max(1, ceiling(log(1.0e-13_qp)/log(abs(spectrum%root(3))/ &
                                                                                  spectrum%modulus)))
    ! zero crossings by linear interpolation between the samples around each
    crossings = 0
    crossing_first = 0.0_qp
    crossing_last = 0.0_qp
    do n = first, size(u) - 1
      if (u(n) == 0.0_dp .or. sign(1.0_dp, u(n)) == sign(1.0_dp, u(n + 1))) cycle
      shift = real(u(n), qp)/real(u(n) - u(n + 1), qp)
      crossings = crossings + 1
      if (crossings == 1) crossing_first = (n - 1) + shift
      crossing_last = (n - 1) + shift
    end do
    call check(name//': at least 20 zero crossings measured', crossings >= 20, integer_text(crossings))
    if (crossings < 20) return
    period_measured = 2.0_qp*(crossing_last - crossing_first)/(crossings - 1)*big_omega/(2.0_qp*pi_qp)
    ! (program period in units of the exact period T) - 1
    period_measured = period_measured - 1.0_qp
    ! The chord's zero of r^t sin(phi t) between samples t_a < t0 < t_b is off
    ! by at most (phi^2/24 + |ln r|/4) step (Taylor at t0: u''/u' = -2 ln r,
    ! u'''/u' ~ -phi^2); only the first and the last crossing enter, so the
    ! period's relative error is at most 2 that/(last - first) in steps.
    bound = 2.0_qp*(spectrum%phase**2/24.0_qp + abs(log(spectrum%modulus))/4.0_qp)/(crossing_last - crossing_first)
    tolerance = bound*(1.0_qp + period_error)
    print '(a, 2es14.6, a, es9.2)', name//': period error of A, measured ', real(period_error, dp), &
      real(period_measured, dp), '  bound ', real(tolerance, dp)
    call check(name//': period from zero crossings = period of A within '//trim(qtoa(tolerance)), &
               abs(period_measured - period_error) <= tolerance, &
               'A '//trim(qtoa(period_error))//', measured '//trim(qtoa(period_measured)))
    ! decay: the window ends where the amplitude has fallen to 1e-3 (beyond, the
    ! program's round-off of ~1e-12 of the amplitude would weigh 1e-9 in D)
    last = size(u) - 2
    if (spectrum%modulus < 1.0_qp) last = min(last, first + floor(log(1.0e-3_qp)/log(spectrum%modulus)))
    casoratian_first = real(u(first + 1), qp)**2 - real(u(first), qp)*real(u(first + 2), qp)
    casoratian_last = real(u(last + 1), qp)**2 - real(u(last), qp)*real(u(last + 2), qp)
    r_measured = (casoratian_last/casoratian_first)**(0.5_qp/(last - first))
    damping_measured = -log(r_measured)/spectrum%phase
    ! D carries the history's error (<= 1e-9 of the amplitude by (a), observed
    ! ~1e-13) over sin^2(phi) ~ 0.3 at an amplitude >= 1e-3: <= 1e-5 relative
    ! at worst, ~1e-9 as observed; its log over 2 (last - first) >= 2 x 600
    ! steps and over phi ~ 0.6 gives xi to 1e-8. Tolerance 1e-8.
    print '(a, 2es14.6)', name//': damping ratio of A, measured ', real(damping, dp), real(damping_measured, dp)
    call check_close(name//': damping ratio from the Casoratian = damping ratio of A', real(damping_measured, dp), &
                     real(damping, dp), 0.0_dp, 1.0e-8_dp)
    if (s%kind == kind_alpha .and. s%alpha_m == 0.0_qp .and. s%alpha_f == 0.0_qp .and. &
        abs(s%beta - 0.25_qp) < 1.0e-30_qp .and. abs(s%gamma - 0.5_qp) < 1.0e-30_qp) then
      call check_close(name//': measured period error = Omega/(2 atan(Omega/2)) - 1 (trapezoidal)', &
        real(period_measured, dp), real(big_omega/(2.0_qp*atan(big_omega/2.0_qp)) - 1.0_qp, dp), 0.0_dp, &
        real(tolerance, dp))
      call check_close(name//': measured damping ratio = 0 (trapezoidal)', real(damping_measured, dp), &
                       0.0_dp, 0.0_dp, 1.0e-8_dp)
    end if
  end subroutine test_measured

  ! ------------------------------------------------------------ (b), (c): closed forms

  !> (b) The spectral radius at Omega -> infinity. It approaches its limit as
  !> c/Omega^2 (HHT, Wilson), c/Omega (Bathe, c = 5) or, for generalized-alpha,
  !> as 0.78 Omega^(-2/3) (observed: its three eigenvalues meet at -rho_inf, and
  !> a triple root moves as the cube root of the O(Omega^-2) perturbation).
  !> So at Omega = 1e4 within 2e-3 (generalized-alpha: 1.7e-3), and at
  !> Omega = 1e12 within 1e-7 (generalized-alpha: 8e-9; quadruple precision
  !> keeps A's entries to ~1e-30, which a triple root turns into ~1e-10).
  subroutine test_limit_radius(s)
    type(scheme_t), intent(in) :: s
    real(qp) :: limit, at_1e4, at_1e9
    type(spectrum_t) :: spectrum
    at_1e4 = radius_at(s, 1.0e4_qp)
    at_1e9 = radius_at(s, 1.0e12_qp)
    if (s%kind == kind_wilson) then
      spectrum = spectrum_of(wilson_limit(s%theta))
      limit = spectrum%radius
      call check(trim(s%name)//': the limit eigenvalue is real and negative (-0.78 for theta = 1.4)', &
        .not. spectrum%oscillating .and. real(spectrum%root(1), qp) < 0.0_qp, trim(qtoa(real(spectrum%root(1), qp))))
    else
      limit = s%radius_infinity
    end if
    print '(a, 3f14.9)', trim(s%name)//': rho(A) at Omega = 1e4, 1e12, closed form ', real(at_1e4, dp), &
      real(at_1e9, dp), real(limit, dp)
    call check_close(trim(s%name)//': rho(A) at Omega = 1e4 = rho_inf within 2e-3', real(at_1e4, dp), &
                     real(limit, dp), 0.0_dp, 2.0e-3_dp)
    call check_close(trim(s%name)//': rho(A) at Omega = 1e12 = rho_inf within 1e-7', real(at_1e9, dp), &
                     real(limit, dp), 0.0_dp, 1.0e-7_dp)
  end subroutine test_limit_radius

  !> Wilson-theta's A as Omega -> infinity in the state (u, h v, h^2 a): with
  !> u_tau -> 0, a_tau = -(6/tau^2) u - (6/tau) v - 2a, and the updates
  !> a1 = a + (a_tau - a)/theta, v1 = v + h(a + a1)/2, u1 = u + h v + h^2(2a + a1)/6.
  pure function wilson_limit(theta) result(a)
    real(qp), intent(in) :: theta
    real(qp) :: a(3, 3)
    real(qp) :: row_a(3)
    row_a = [-6.0_qp/theta**3, -6.0_qp/theta**2, 1.0_qp - 3.0_qp/theta]
    a(3, :) = row_a
    a(2, :) = [0.0_qp, 1.0_qp, 0.5_qp] + 0.5_qp*row_a
    a(1, :) = [1.0_qp, 1.0_qp, 1.0_qp/3.0_qp] + row_a/6.0_qp
  end function wilson_limit

  !> (c) Closed forms at dt/T = 0.1 and elsewhere: the trapezoidal rule's phase
  !> 2 atan(Omega/2) with |lambda| = 1; the linear acceleration method's
  !> cos(phi) = 1 - Omega^2/(2 (1 + Omega^2/6)), |lambda| = 1; Wilson theta = 1
  !> and Newmark beta = 1/6 are the same matrix; all schemes are second-order
  !> accurate: the period error at 0.05 is ~1/4 of that at 0.1.
  subroutine test_closed_forms()
    type(spectrum_t) :: spectrum
    real(qp) :: big_omega, worst, ratio
    integer :: j
    print '(a)', 'integrator                          period error   damping ratio   rho(A)   (dt/T = 0.1)'
    do j = 1, size(schemes)
      spectrum = spectrum_at(schemes(j), 0.2_qp*pi_qp)
      print '(a36, es14.5, es15.5, f10.6)', schemes(j)%name, real(0.2_qp*pi_qp/spectrum%phase - 1.0_qp, dp), &
        real(-log(spectrum%modulus)/spectrum%phase, dp), real(spectrum%radius, dp)
      ratio = (pi_qp*0.1_qp/phase_at(schemes(j), 0.1_qp*pi_qp) - 1.0_qp)/ &
              (0.2_qp*pi_qp/spectrum%phase - 1.0_qp)
      ! second order: PE(h/2)/PE(h) = 1/4 + O(Omega^2) (Omega^2 = 0.4: within 0.05)
      call check_close(trim(schemes(j)%name)//': second order, period error at dt/T = 0.05 / at 0.1 = 1/4', &
                       real(ratio, dp), 0.25_dp, 0.0_dp, 0.05_dp)
      call check(trim(schemes(j)%name)//': no growth at dt/T = 0.1 (rho <= 1)', spectrum%radius <= 1.0_qp + 1.0e-25_qp)
    end do
    worst = 0.0_qp
    do j = 1, 60
      big_omega = 0.1_qp*j
      spectrum = spectrum_at(newmark(0.25_qp, 0.5_qp), big_omega)
      worst = max(worst, abs(spectrum%phase - 2.0_qp*atan(big_omega/2.0_qp)), abs(spectrum%modulus - 1.0_qp))
      spectrum = spectrum_at(newmark(1.0_qp/6.0_qp, 0.5_qp), big_omega*0.5_qp)   ! inside its limit 3.46
      worst = max(worst, abs(cos(spectrum%phase) - (1.0_qp - (big_omega*0.5_qp)**2/ &
        (2.0_qp*(1.0_qp + (big_omega*0.5_qp)**2/6.0_qp)))), abs(spectrum%modulus - 1.0_qp))
      worst = max(worst, maxval(abs(amplification(wilson(1.0_qp), 1.0_qp, big_omega) - &
                                    amplification(newmark(1.0_qp/6.0_qp, 0.5_qp), 1.0_qp, big_omega))))
    end do
    ! quadruple precision: the eigenvalues to ~1e-30 of their size (1e-25 leaves Newton's last bits)
    call check('closed forms: trapezoidal phase 2 atan(Omega/2), |lambda| = 1; linear acceleration cos(phi), '// &
               '|lambda| = 1; Wilson theta = 1 = Newmark 1/6, 1/2 (Omega 0.1 ... 6, to 1e-25)', worst < 1.0e-25_qp, &
               'worst '//trim(qtoa(worst)))
  end subroutine test_closed_forms

  ! ------------------------------------------------------------ (d) stability limits

  !> The Omega where rho(A) first exceeds 1 (bisection in [low, high], rho(low) <= 1 < rho(high)).
  real(qp) function stability_limit(s, low_start, high_start) result(limit)
    type(scheme_t), intent(in) :: s
    real(qp), intent(in) :: low_start, high_start
    real(qp) :: low, high, middle
    integer :: iteration
    low = low_start
    high = high_start
    do iteration = 1, 200
      middle = 0.5_qp*(low + high)
      if (radius_at(s, middle) > 1.0_qp + 1.0e-24_qp) then
        high = middle
      else
        low = middle
      end if
    end do
    limit = 0.5_qp*(low + high)
  end function stability_limit

  !> (d) Newmark 1/6 (= Wilson theta = 1): stable up to 2 sqrt(3) exactly; the
  !> program runs at 0.9 of it (the exact discrete max E_n/E_0 is 5.3: near the
  !> limit it grows like 1/(1 - (Omega/2 sqrt(3))^2); the solver's growth-rate
  !> guard, growth by 1.5 in each of 3 steps, acts only past 10 times the input,
  !> so this stable run goes on) and stops with the instability error at 1.001
  !> of it (|lambda| = 1.05: the energy passes 100 E_0 within ~50 steps).
  !> Wilson theta = 1.2: rho > 1 at large Omega.
  subroutine test_stability_limits()
    type(scheme_t) :: linear, wilson_one, wilson_low
    real(qp) :: limit, critical, big_omega, ratio
    character(len=40) :: label
    type(scheme_t) :: runs(2)
    integer :: j
    linear = newmark(1.0_qp/6.0_qp, 0.5_qp)
    wilson_one = wilson(1.0_qp)
    wilson_low = wilson(1.2_qp)
    critical = 2.0_qp*sqrt(3.0_qp)
    ! The bisection's threshold 1e-24 over rho's growth ~ sqrt(8 d/3) past the
    ! limit puts the limit within ~1e-45 (d = relative excess); 1e-20 is round-off.
    limit = stability_limit(linear, 1.0_qp, 10.0_qp)
    call check_close('NEWMARK 1/6, 1/2: stability limit Omega = 2 sqrt(3) (bisection on rho(A))', &
                     real(limit, dp), real(critical, dp), 1.0e-15_dp)
    limit = stability_limit(wilson_one, 1.0_qp, 10.0_qp)
    call check_close('WILSON theta=1: stability limit Omega = 2 sqrt(3)', real(limit, dp), real(critical, dp), &
                     1.0e-15_dp)
    call check('WILSON theta=1: only conditionally stable, rho(A) > 1 at Omega = 1e4', &
               radius_at(wilson_one, 1.0e4_qp) > 1.0_qp)
    call check('WILSON theta=1.2: only conditionally stable, rho(A) > 1 at Omega = 1e4', &
               radius_at(wilson_low, 1.0e4_qp) > 1.0_qp)
    limit = stability_limit(wilson_low, 1.0_qp, 1.0e4_qp)
    print '(a, f12.6)', 'WILSON theta=1.2: stability limit Omega = ', real(limit, dp)
    call check('WILSON theta=1.2: its limit lies above 2 sqrt(3) (theta widens the stable range)', limit > critical)
    call check('WILSON theta=1.37 and 1.4: rho(A) <= 1 at Omega = 1e4 (unconditionally stable)', &
               radius_at(wilson(1.37_qp), 1.0e4_qp) <= 1.0_qp .and. &
               radius_at(wilson(1.4_qp), 1.0e4_qp) <= 1.0_qp)
    runs = [linear, wilson_one]
    do j = 1, size(runs)
      big_omega = 0.9_qp*critical
      ratio = big_omega/(2.0_qp*pi_qp)
      call test_history(runs(j), real(ratio, dp), 300, .false.)
      big_omega = 1.001_qp*critical
      write(label, '(a)') trim(runs(j)%name)
      call test_unstable_run(runs(j), real(big_omega/(2.0_qp*pi_qp), dp), trim(label))
    end do
  end subroutine test_stability_limits

  !> The program stops with the instability error at dt/T = ratio.
  subroutine test_unstable_run(s, ratio, label)
    type(scheme_t), intent(in) :: s
    real(dp), intent(in) :: ratio
    character(*), intent(in) :: label
    character(:), allocatable :: path
    type(record_t) :: record
    type(error_t), allocatable :: error
    real(dp) :: dt
    path = folder//'/unstable_'//file_tag(s%name)//'.inp'
    dt = ratio*2.0_dp*acos(-1.0_dp)/sqrt(real(omega2, dp))
    call write_dynamic_deck(path, s, dt, 2000)
    call run_deck(path, folder//'/out', record, error)
    call check(label//': at 1.001 x 2 sqrt(3) the run stops as unstable', allocated(error))
    if (allocated(error)) then
      print '(a)', label//': '//error_text(error)
      call check(label//': the error says the energy has grown', index(error_text(error), 'energy') > 0, &
                 error_text(error))
    end if
  end subroutine test_unstable_run
end program test_integrators
