!> Verification of the Wilson-theta integrator (src/dynamics/visco2d_dynamic.f90, eqs. [34]-[42])
!> against independent computations:
!>   1. A single degree of freedom: one plane-strain element in uniaxial strain
!>      (bottom fixed, top free in z only), k/m = 2 M_c/(rho h^2) with the
!>      constrained modulus M_c = K + 4G/3, checked by a static run. Started with
!>      a velocity v0, its displacement history must equal e1^T A^n x0 with A the
!>      amplification matrix of Bathe and Wilson's scalar method in its textbook
!>      (total) form, coded here again in quadruple precision. The period
!>      elongation and amplitude decay of A's principal roots are compared with
!>      those measured from the program's own time series; their orders, the
!>      unconditional stability of theta = 1.4 and the stability limit of the
!>      linear acceleration method (theta = 1: dt/T = sqrt(3)/pi) are checked.
!>      The energy of the SDOF is compared with its exact discrete value.
!>   2. A free-flying elastic sphere (inputs/free_flight.inp) under gravity:
!>      a constant acceleration is integrated exactly, so the centre of mass,
!>      every node and the energy balance must follow the closed form to
!>      round-off, also with two TIME stages and over 1e5 steps.
!> Tolerances are round-off models (a few eps per step, accumulated over the
!> n steps run), each explained where it is used. Where the program stops a
!> stable run (its energy-growth guard trips on Wilson-theta's first-step
!> overshoot, E_1/E_0 > 100 from dt/T = 3.22 on), the row is checked for that
!> reason and is otherwise analytic only.
program test_wilson
  use visco2d_kinds, only: dp, whole_body_factor
  use visco2d_error, only: error_t, error_text
  use visco2d_deck, only: deck_t, read_deck
  use visco2d_dynamic, only: solve_dynamic, energy_growth_limit
  use visco2d_static, only: solve_static, static_solution_t
  use visco2d_assembly, only: lumped_mass, node_dof
  use visco2d_record, only: record_t
  use visco2d_driver, only: run_deck
  use visco2d_expect, only: summary_value
  use visco2d_strings, only: integer_text
  use visco2d_testing, only: check, check_close, test_summary, write_deck, history_index
  use visco2d_spectrum, only: qp, pi_qp, spectrum_t, spectrum_of, cubic
  implicit none

  real(dp), parameter :: eps = epsilon(1.0_dp)
  character(*), parameter :: folder = 'build/test-tmp/wilson'

  ! The SDOF: a w x h plane-strain block.
  real(dp), parameter :: block_width = 0.04_dp, block_height = 0.01_dp
  real(dp), parameter :: block_young = 1.0e6_dp, block_poisson = 0.25_dp, block_density = 1000.0_dp
  real(dp), parameter :: block_velocity = 0.1_dp
  real(dp), parameter :: ratios(10) = [0.01_dp, 0.02_dp, 0.05_dp, 0.1_dp, 0.2_dp, 0.5_dp, 1.0_dp, 2.0_dp, &
                                       5.0_dp, 10.0_dp]
  real(dp), parameter :: theta_usual = 1.4_dp


  !> One row of the period elongation / amplitude decay table.
  type :: table_row_t
    real(dp) :: ratio = 0.0_dp
    logical :: oscillating = .false., ran = .false., measured = .false.
    real(qp) :: pe = 0.0_qp, ad = 0.0_qp, pe_measured = 0.0_qp, ad_measured = 0.0_qp
    real(qp) :: radius = 0.0_qp, dominant = 0.0_qp, dominant_measured = 0.0_qp
    real(dp) :: history_error = 0.0_dp, overshoot = 0.0_dp
    real(qp) :: pe_difference = 0.0_qp, ad_difference = 0.0_qp
  end type table_row_t

  type(table_row_t) :: rows(size(ratios))
  real(qp) :: omega2
  integer :: k

  call execute_command_line('mkdir -p '//folder)

  omega2 = sdof_omega2()
  call test_sdof_stiffness()
  call test_spectrum_solver()
  do k = 1, size(ratios)
    call test_sdof_history(ratios(k), theta_usual, rows(k))
  end do
  call print_table()
  call test_orders()
  call test_stability()
  call test_linear_acceleration_program()
  call test_free_flight_deck()
  call test_free_flight_two_stages()
  call test_free_flight_long_run()
  call test_summary('test_wilson')

contains

  ! ---------------------------------------------------------------- the SDOF

  !> omega^2 = k/m of the block in closed form: the top nodes carry half the
  !> uniaxial-strain force M_c (u/h) w each and a quarter of the mass rho w h.
  real(qp) function sdof_omega2() result(value)
    real(qp) :: bulk, shear
    bulk = real(block_young, qp)/(3.0_qp*(1.0_qp - 2.0_qp*real(block_poisson, qp)))
    shear = real(block_young, qp)/(2.0_qp*(1.0_qp + real(block_poisson, qp)))
    value = 2.0_qp*(bulk + 4.0_qp*shear/3.0_qp)/(real(block_density, qp)*real(block_height, qp)**2)
  end function sdof_omega2

  !> A real number for a deck card, to full double precision.
  function num(value) result(text)
    real(dp), intent(in) :: value
    character(:), allocatable :: text
    character(len=32) :: buffer
    write(buffer, '(es25.17e3)') value
    text = trim(adjustl(buffer))
  end function num

  !> The block's cards up to the analysis-specific ones.
  function block_lines(analysis) result(lines)
    character(*), intent(in) :: analysis
    character(len=200), allocatable :: lines(:)
    lines = [character(len=200) :: &
      'TITLE Wilson-theta SDOF: one plane-strain element in uniaxial strain', &
      'ANALYSIS '//analysis, 'GEOMETRY PLANESTRAIN', &
      'MATERIAL block ELASTIC E='//num(block_young)//' NU='//num(block_poisson)//' RHO='//num(block_density), &
      'NODE 1 0 0', 'NODE 2 '//num(block_width)//' 0', 'NODE 3 '//num(block_width)//' '//num(block_height), &
      'NODE 4 0 '//num(block_height), 'ELEMENT 1 1 2 3 4', &
      'FIX 1 RZ', 'FIX 2 RZ', 'FIX 3 R', 'FIX 4 R']
  end function block_lines

  !> The dynamic SDOF deck: v0 on the top nodes, steps of dt, theta.
  subroutine write_sdof_deck(path, dt, steps, theta)
    character(*), intent(in) :: path
    real(dp), intent(in) :: dt, theta
    integer, intent(in) :: steps
    call write_deck(path, [character(len=200) :: block_lines('DYNAMIC'), &
      'INITIAL VZ='//num(block_velocity), 'WILSON THETA='//num(theta), &
      'TIME DT='//num(dt)//' TEND='//num(steps*dt), 'OUTPUT EVERY=1', 'PROBE top NODE=3', &
      'PROBE top_left NODE=4', 'END'])
  end subroutine write_sdof_deck

  !> omega^2 independently of the closed form: k from a static run (FORCE on the
  !> two top nodes, k = F/u), m from the program's lumped mass of a top node.
  !> Both are exact for this uniform-strain element, so they agree to round-off
  !> of the static solve (a 2-equation system): 1e-12.
  subroutine test_sdof_stiffness()
    character(*), parameter :: path = folder//'/sdof_static.inp'
    real(dp), parameter :: force = 1.0e3_dp
    type(deck_t) :: deck
    type(static_solution_t) :: solution
    type(error_t), allocatable :: error
    real(dp), allocatable :: mass(:)
    real(qp) :: stiffness, node_mass, constrained, omega2_tilt
    call write_deck(path, [character(len=200) :: block_lines('STATIC'), &
      'FORCE 3 FZ='//num(force), 'FORCE 4 FZ='//num(force), 'END'])
    call read_deck(path, deck, error)
    if (allocated(error)) then
      call check('sdof static deck reads', .false., error_text(error)); return
    end if
    call solve_static(deck%mesh, deck%materials, deck%settings, deck%loads, deck%source, solution, error)
    if (allocated(error)) then
      call check('sdof static run', .false., error_text(error)); return
    end if
    associate (u3 => solution%displacement(2, 3), u4 => solution%displacement(2, 4))
    call check_close('sdof static: both top nodes move alike', u4, u3, 1.0e-12_dp)
    stiffness = real(force, qp)/real(u3, qp)
    end associate
    mass = lumped_mass(deck%mesh, deck%settings, deck%materials)
    node_mass = real(mass(node_dof(deck%mesh, 3, 2)), qp)
    call check_close('sdof lumped mass of a top node = rho w h/4 (symmetry)', real(node_mass, dp), &
                     block_density*block_width*block_height/4.0_dp, 1.0e-14_dp)
    call check_close('sdof omega^2 = k_static/m_lumped = 2 M_c/(rho h^2)', real(stiffness/node_mass, dp), &
                     real(omega2, dp), 1.0e-12_dp)
    ! M_c from the program's K and G against E (1 - nu)/((1 + nu)(1 - 2 nu)).
    constrained = real(deck%materials(1)%bulk, qp) + 4.0_qp*real(deck%materials(1)%shear, qp)/3.0_qp
    call check_close('sdof M_c = K + 4G/3 = E(1-nu)/((1+nu)(1-2nu))', real(constrained, dp), &
      block_young*(1.0_dp - block_poisson)/((1.0_dp + block_poisson)*(1.0_dp - 2.0_dp*block_poisson)), 1.0e-14_dp)

    ! The block has a second mode: the two top nodes moving opposite (a tilt
    ! of the top edge). Symmetric data never excite it beyond round-off, but
    ! an unstable integrator (theta = 1 above its limit) would blow that up.
    ! The wide block (w = 4 h) puts it below the uniform-strain mode, so that
    ! at the theta = 1 steps used below (dt/T <= 0.6) it stays inside the
    ! stability limit: omega_tilt < omega/1.5 gives dt/T_tilt < 0.4 < 0.55.
    call write_deck(path, [character(len=200) :: block_lines('STATIC'), &
      'FORCE 3 FZ='//num(force), 'FORCE 4 FZ='//num(-force), 'END'])
    call read_deck(path, deck, error)
    if (.not. allocated(error)) call solve_static(deck%mesh, deck%materials, deck%settings, deck%loads, deck%source, &
      solution, error)
    if (allocated(error)) then
      call check('sdof static tilt run', .false., error_text(error)); return
    end if
    associate (u3 => solution%displacement(2, 3), u4 => solution%displacement(2, 4))
    call check_close('sdof static tilt: top nodes move opposite', u4, -u3, 1.0e-12_dp)
    omega2_tilt = real(force, qp)/real(u3, qp)/node_mass
    end associate
    print '(a, f8.5)', 'sdof: omega_tilt/omega = ', real(sqrt(omega2_tilt/omega2), dp)
    call check('sdof: the tilt mode is below omega/1.5', sqrt(omega2_tilt/omega2) < 1.0_qp/1.5_qp)
  end subroutine test_sdof_stiffness

  !> One step of the scalar Wilson-theta method in Bathe and Wilson's total
  !> (textbook) form, no load: x = (u, v, a), m = 1, k = omega^2.
  pure function wilson_step(x, w2, h, theta) result(next)
    real(qp), intent(in) :: x(3), w2, h, theta
    real(qp) :: next(3)
    real(qp) :: tau, u_tau, a_tau, a1
    tau = theta*h
    u_tau = (6.0_qp/tau**2*x(1) + 6.0_qp/tau*x(2) + 2.0_qp*x(3))/(w2 + 6.0_qp/tau**2)
    a_tau = 6.0_qp/tau**2*(u_tau - x(1)) - 6.0_qp/tau*x(2) - 2.0_qp*x(3)
    a1 = x(3) + (a_tau - x(3))/theta
    next(1) = x(1) + h*x(2) + h**2/6.0_qp*(2.0_qp*x(3) + a1)
    next(2) = x(2) + h/2.0_qp*(x(3) + a1)
    next(3) = a1
  end function wilson_step

  !> The amplification matrix: x_{n+1} = A x_n, column j = the step of unit vector j.
  pure function amplification(w2, h, theta) result(a)
    real(qp), intent(in) :: w2, h, theta
    real(qp) :: a(3, 3)
    real(qp) :: unit(3)
    integer :: j
    do j = 1, 3
      unit = 0.0_qp
      unit(j) = 1.0_qp
      a(:, j) = wilson_step(unit, w2, h, theta)
    end do
  end function amplification

  !> A at a step ratio dt/T (omega = 1).
  pure function amplification_at(ratio, theta) result(a)
    real(qp), intent(in) :: ratio, theta
    real(qp) :: a(3, 3)
    a = amplification(1.0_qp, 2.0_qp*pi_qp*ratio, theta)
  end function amplification_at


  !> Period elongation and amplitude decay per cycle of a complex pair r e^{+-i phi}
  !> at step ratio dt/T: PE = 2 pi (dt/T)/phi - 1, AD = 1 - r^(2 pi/phi).
  pure subroutine elongation_decay(ratio, modulus, phase, pe, ad)
    real(qp), intent(in) :: ratio, modulus, phase
    real(qp), intent(out) :: pe, ad
    pe = 2.0_qp*pi_qp*ratio/phase - 1.0_qp
    ad = 1.0_qp - modulus**(2.0_qp*pi_qp/phase)
  end subroutine elongation_decay

  !> The root finder on matrices with known roots, and Vieta's relations on A.
  subroutine test_spectrum_solver()
    real(qp) :: a(3, 3), known(3, 3)
    type(spectrum_t) :: s
    integer :: k
    real(qp) :: worst
    ! A companion-like triangular matrix with roots 0.9 e^{+-0.3i} and -0.2 (block form).
    known = 0.0_qp
    known(1, 1) = 0.9_qp*cos(0.3_qp)
    known(1, 2) = -0.9_qp*sin(0.3_qp)
    known(2, 1) = 0.9_qp*sin(0.3_qp)
    known(2, 2) = 0.9_qp*cos(0.3_qp)
    known(3, 3) = -0.2_qp
    known(1, 3) = 0.7_qp
    s = spectrum_of(known)
    call check('spectrum: a known rotation block is oscillating', s%oscillating)
    call check_close('spectrum: known modulus 0.9', real(s%modulus, dp), 0.9_dp, 1.0e-15_dp)
    call check_close('spectrum: known phase 0.3', real(s%phase, dp), 0.3_dp, 1.0e-15_dp)
    call check_close('spectrum: known real root -0.2', real(real(s%root(3), qp), dp), -0.2_dp, 1.0e-15_dp)
    ! Three real roots 2, -1, 0.5 (upper triangular).
    known = 0.0_qp
    known(1, 1) = 0.5_qp
    known(2, 2) = -1.0_qp
    known(3, 3) = 2.0_qp
    known(1, 2) = 3.0_qp
    known(2, 3) = -4.0_qp
    s = spectrum_of(known)
    call check('spectrum: real roots found real', .not. s%oscillating)
    call check('spectrum: real roots by decreasing modulus 2, -1, 0.5', &
      abs(s%root(1) - 2.0_qp) < 1.0e-30_qp .and. abs(s%root(2) + 1.0_qp) < 1.0e-30_qp .and. &
      abs(s%root(3) - 0.5_qp) < 1.0e-30_qp)
    ! Vieta on the Wilson matrices of the table: sum of roots = trace, product = det,
    ! to quadruple-precision round-off (1e-28 of the scale of the coefficients).
    worst = 0.0_qp
    do k = 1, size(ratios)
      a = amplification_at(real(ratios(k), qp), real(theta_usual, qp))
      s = spectrum_of(a)
      worst = max(worst, abs(sum(s%root) + s%coefficients(2)), &
                  abs(product(s%root) + s%coefficients(0)), maxval(abs(cubic_all(s))))
    end do
    call check('spectrum: Wilson roots satisfy Vieta and p(lambda) = 0 to 1e-28', worst < 1.0e-28_qp, &
               'worst '//trim(qtoa(worst)))
  end subroutine test_spectrum_solver

  function cubic_all(s) result(values)
    type(spectrum_t), intent(in) :: s
    complex(qp) :: values(3)
    integer :: j
    do j = 1, 3
      values(j) = cubic(s%coefficients, s%root(j))
    end do
  end function cubic_all

  function qtoa(value) result(text)
    real(qp), intent(in) :: value
    character(len=24) :: text
    write(text, '(es12.4)') real(value, dp)
  end function qtoa

  !> The SDOF displacement of a run: the mean of the two top nodes' u_z. The
  !> mean removes the tilt mode (u3 = -u4) that round-off excites, which is
  !> no part of the SDOF and, at large dt/T, decays more slowly than it.
  function sdof_displacement(record) result(u)
    type(record_t), intent(in) :: record
    real(dp), allocatable :: u(:)
    integer :: right, left
    right = history_index(record, 'top_uz_m')
    left = history_index(record, 'top_left_uz_m')
    if (right == 0 .or. left == 0) then
      allocate(u(0))
      return
    end if
    u = 0.5_dp*(record%history(right, 1:record%nrow) + record%history(left, 1:record%nrow))
  end function sdof_displacement

  !> The SDOF at one step ratio: run the program, compare the displacement
  !> history with e1^T A^n x0, measure PE/AD (or the dominant real root) from
  !> the series, check the energy against its exact discrete value.
  subroutine test_sdof_history(ratio, theta, row)
    real(dp), intent(in) :: ratio, theta
    type(table_row_t), intent(out) :: row
    character(len=8) :: tag
    character(:), allocatable :: path, name
    type(deck_t) :: deck
    type(record_t) :: record
    type(error_t), allocatable :: error
    type(spectrum_t) :: s
    real(qp) :: a(3, 3), x(3), h, w2, v0, e0_exact, worst, scale, spurious, decay, c1, c0, modulus, phase
    real(qp), allocatable :: u_exact(:), energy_exact(:)
    real(dp), allocatable :: u(:), energy(:), balance(:)
    real(dp) :: period, tolerance
    integer :: steps, n, first, last, col_u, col_k, col_s, col_b, col_d, col_x, col_g
    logical :: monotone
    write(tag, '(f8.2)') ratio
    name = 'sdof dt/T='//trim(adjustl(tag))
    row%ratio = ratio
    w2 = omega2
    ! Enough steps for 10 cycles and for the spurious root to die out (300 at least).
    steps = max(300, ceiling(10.0_dp/ratio))
    path = folder//'/sdof_'//trim(adjustl(tag))//'.inp'
    call write_sdof_deck(path, ratio*2.0_dp*acos(-1.0_dp)/sqrt(real(w2, dp)), steps, theta)
    call read_deck(path, deck, error)
    if (allocated(error)) then
      call check(name//': deck reads', .false., error_text(error)); return
    end if
    call check(name//': '//integer_text(steps)//' steps of one stage', deck%stages(1)%steps == steps .and. &
               size(deck%stages) == 1)
    ! The analytic model uses the program's own dt and v0.
    h = real(deck%stages(1)%dt, qp)
    v0 = real(deck%dynamics%velocity(2), qp)
    a = amplification(w2, h, real(theta, qp))
    s = spectrum_of(a)
    row%oscillating = s%oscillating
    row%radius = s%radius
    if (s%oscillating) then
      call elongation_decay(h*sqrt(w2)/(2.0_qp*pi_qp), s%modulus, s%phase, row%pe, row%ad)
    else
      row%dominant = real(s%root(1), qp)
    end if
    allocate(u_exact(0:steps), energy_exact(0:steps))
    x = [0.0_qp, v0, 0.0_qp]                  ! a(0) = 0: equilibrium with u = 0 and no load
    e0_exact = 0.5_qp*v0**2
    u_exact(0) = 0.0_qp
    energy_exact(0) = 1.0_qp
    do n = 1, steps
      x = matmul(a, x)
      u_exact(n) = x(1)
      energy_exact(n) = 0.5_qp*(x(2)**2 + w2*x(1)**2)/e0_exact
    end do
    row%overshoot = real(maxval(energy_exact) - 1.0_qp, dp)

    call solve_dynamic(deck, record, error)
    if (allocated(error)) then
      ! The run stops when kinetic + internal energy exceeds energy_growth_limit
      ! times the energy put in. Wilson-theta overshoots on its first step
      ! (u_1 ~ (1 - 1/theta^2) v0 dt for omega dt >> 1), so E_1/E_0 grows like
      ! (omega dt)^2 although the method is stable. The stop is accepted only
      ! where the exact discrete energy does exceed the limit.
      call check(name//': the run stops only where the exact Wilson energy exceeds '// &
        'energy_growth_limit*E0 (first-step overshoot, E1/E0 = '//trim(qtoa(energy_exact(1)))//')', &
        maxval(energy_exact) > energy_growth_limit .and. index(error_text(error), 'grown past') > 0, &
        error_text(error))
      print '(a)', 'NOTE '//name//': the program stops as unstable although rho(A) = '//trim(qtoa(s%radius))// &
        ' < 1: the first-step overshoot of the energy, '//trim(qtoa(energy_exact(1)))//' E0, exceeds '// &
        'energy_growth_limit; no program data for this row'
      return
    end if
    row%ran = .true.
    col_u = history_index(record, 'top_left_uz_m')
    col_k = history_index(record, 'kinetic_J')
    col_s = history_index(record, 'strain_J')
    col_b = history_index(record, 'balance_error_J')
    col_d = history_index(record, 'dissipated_J')
    col_x = history_index(record, 'external_work_J')
    col_g = history_index(record, 'gravity_work_J')
    call check(name//': history has every step', record%nrow == steps + 1 .and. &
               all([col_u, col_k, col_s, col_b, col_d, col_x, col_g] > 0))
    if (record%nrow /= steps + 1) return
    u = sdof_displacement(record)
    energy = record%history(col_k, 1:steps + 1) + record%history(col_s, 1:steps + 1)
    balance = record%history(col_b, 1:steps + 1)

    ! (a) u_n = e1^T A^n x0. Each step rounds the state to a few eps of its
    ! size; with rho(A) <= 1 those errors are carried, not amplified, so the
    ! error after n steps is below c n eps max|u|. c = 20 covers the ~10
    ! rounded operations of a step (solve, eq. [37]-[39] updates).
    scale = maxval(abs(u_exact))
    worst = maxval(abs(real(u, qp) - u_exact))/scale
    row%history_error = real(worst, dp)
    tolerance = 20.0_dp*steps*eps
    call check(name//': the tilt mode stays at round-off: |u3 - u4| <= 20 n eps max|u|', &
      maxval(abs(record%history(col_u, 1:steps + 1) - record%history(history_index(record, 'top_uz_m'), 1:steps + 1))) &
      <= tolerance*real(scale, dp))
    call check(name//': u_n = e1^T A^n x0 (rel. to max|u|) within 20 n eps = '//trim(qtoa(real(tolerance, qp))), &
               worst <= tolerance, 'error '//trim(qtoa(worst)))

    ! (b) PE and AD measured from the series: least squares on
    ! u_{n+2} = c1 u_{n+1} + c0 u_n + d, where c1 = 2 r cos(phi), c0 = -r^2
    ! for the principal pair and d absorbs a constant offset: the program
    ! accumulates the stress from increments (sigma += D d(eps)), so round-off
    ! leaves sigma and u apart by a few eps of their largest size for good,
    ! a mode of eigenvalue 1 (here ~1e-15 of max|u|) that stays when the
    ! oscillation has decayed. The window starts where the spurious root is
    ! below 1e-17 of the pair ((|lambda3|/r)^n) and ends where the pair has
    ! decayed by 1e-12 (r^n), before the offset's own round-off matters.
    ! Where the principal roots are real, the dominant one is measured the
    ! same way from u_{n+1} = lambda u_n + d.
    if (s%oscillating) then
      spurious = abs(s%root(3))/s%modulus
      decay = s%modulus
    else
      spurious = abs(s%root(2))/abs(s%root(1))
      decay = abs(s%root(1))
    end if
    first = ceiling(log(1.0e-17_qp)/log(max(spurious, 1.0e-30_qp)))
    last = steps
    if (decay < 1.0_qp) last = min(steps, floor(log(1.0e-12_qp)/log(decay)))
    if (last - first >= 10) then
      row%measured = .true.
      if (s%oscillating) then
        call fit_recurrence(real(u(first + 1:last + 1), qp), c1, c0)
        modulus = sqrt(-c0)
        phase = acos(c1/(2.0_qp*modulus))
        call elongation_decay(h*sqrt(w2)/(2.0_qp*pi_qp), modulus, phase, row%pe_measured, row%ad_measured)
        ! The series obeys the recurrence up to its per-step rounding, a few
        ! eps (the error accumulated in (a) is itself a solution of the
        ! recurrence and does not bias the fit). PE is the most sensitive
        ! at the smallest phase: ~1/phi^3 = 4e3 at phi = 0.063 (dt/T = 0.01),
        ! so 10 eps/phi^3 ~ 1e-11 bounds every row (observed: <= 1e-14).
        tolerance = 1.0e-11_dp
        call check_close(name//': PE measured from the series = PE of A', real(row%pe_measured, dp), &
                         real(row%pe, dp), 0.0_dp, tolerance)
        call check_close(name//': AD measured from the series = AD of A', real(row%ad_measured, dp), &
                         real(row%ad, dp), 0.0_dp, tolerance)
        row%pe_difference = abs(row%pe_measured - row%pe)
        row%ad_difference = abs(row%ad_measured - row%ad)
      else
        call fit_ratio(real(u(first + 1:last + 1), qp), row%dominant_measured)
        call check(name//': dominant real root measured from the series = root of A', &
                   abs(row%dominant_measured - row%dominant) <= 1.0e-12_qp, &
                   'measured '//trim(qtoa(row%dominant_measured))//', analytic '//trim(qtoa(row%dominant)))
      end if
    end if

    ! (c) Energy. For this elastic SDOF without loads the balance error is
    ! exactly E_n - E_0 (kinetic + strain, trapezoidal work exact for a linear
    ! force), and E_n/E_0 = (v_n^2 + omega^2 u_n^2)/v0^2 of the exact discrete
    ! solution: the same 20 n eps model as (a), doubled (E is quadratic).
    tolerance = 40.0_dp*steps*eps
    call check(name//': no external, gravity or support work', all(record%history(col_x, 1:steps + 1) == 0.0_dp) &
               .and. all(record%history(col_g, 1:steps + 1) == 0.0_dp))
    call check(name//': dissipated = internal work - strain energy = 0 (elastic)', &
               maxval(abs(record%history(col_d, 1:steps + 1)))/energy(1) <= tolerance)
    call check(name//': balance_error = E_n - E_0', &
               maxval(abs(balance - (energy - energy(1))))/energy(1) <= tolerance)
    worst = maxval(abs(real(energy/energy(1), qp) - energy_exact))
    call check(name//': E_n/E_0 = exact discrete energy of A^n x0', worst <= tolerance, &
               'error '//trim(qtoa(worst)))
    ! Wilson-theta does not decrease E at every step: E_n exceeds E_0 within
    ! the first cycle by O((omega dt)^2) (the quadratic form A contracts is not
    ! E). What decreases is the energy per cycle: the maximum of E_n over each
    ! numerical period 2 pi/phi never grows; where the principal roots are real
    ! (no cycle) E_n decreases after the first step. Slack: 1e-12 relative,
    ! and 1e-20 E0 absolute for the round-off floor: the offset mode of (b)
    ! (~1e-15 of max|u|, eigenvalue 1) keeps ~1e-30 E0 for good, so once the
    ! motion has decayed below that, E_n is round-off.
    if (s%oscillating) then
      period = real(2.0_qp*pi_qp/s%phase, dp)
      monotone = cycle_maxima_decrease(energy, period, 1.0e-12_dp, 1.0e-20_dp*energy(1))
      call check(name//': max of kinetic + strain over each numerical period never grows', monotone)
    else
      call check(name//': kinetic + strain decreases after the first step (no oscillation)', &
                 all(energy(3:) <= energy(2:steps)*(1.0_dp + 1.0e-12_dp) + 1.0e-20_dp*energy(1)))
    end if
    call check(name//': energy at the end below the initial', energy(steps + 1) < energy(1))
    call check_close(name//': largest balance error / E0 = exact overshoot max(E_n/E_0) - 1', &
                     maxval(balance)/energy(1), row%overshoot, 0.0_dp, tolerance)
  end subroutine test_sdof_history

  !> Least squares u_{n+2} = c1 u_{n+1} + c0 u_n + d over the whole series.
  subroutine fit_recurrence(u, c1, c0)
    real(qp), intent(in) :: u(:)
    real(qp), intent(out) :: c1, c0
    real(qp) :: x(3)
    integer :: m, j
    m = size(u)
    x = least_squares(reshape([u(2:m - 1), u(1:m - 2), [(1.0_qp, j = 1, m - 2)]], [m - 2, 3]), u(3:m))
    c1 = x(1)
    c0 = x(2)
  end subroutine fit_recurrence

  !> Least squares u_{n+1} = lambda u_n + d over the whole series.
  subroutine fit_ratio(u, lambda)
    real(qp), intent(in) :: u(:)
    real(qp), intent(out) :: lambda
    real(qp) :: x(2)
    integer :: m, j
    m = size(u)
    x = least_squares(reshape([u(1:m - 1), [(1.0_qp, j = 1, m - 1)]], [m - 1, 2]), u(2:m))
    lambda = x(1)
  end subroutine fit_ratio

  !> min |X c - y| by the normal equations, solved by Gaussian elimination
  !> with partial pivoting (quadruple precision: the squared condition of
  !> these small well-scaled systems stays far inside it).
  function least_squares(x, y) result(c)
    real(qp), intent(in) :: x(:, :), y(:)
    real(qp) :: c(size(x, 2))
    real(qp) :: normal(size(x, 2), size(x, 2) + 1), pivot_row(size(x, 2) + 1)
    integer :: i, j, p, n
    n = size(x, 2)
    normal(:, 1:n) = matmul(transpose(x), x)
    normal(:, n + 1) = matmul(transpose(x), y)
    do j = 1, n
      p = j - 1 + maxloc(abs(normal(j:n, j)), 1)
      pivot_row = normal(p, :)
      normal(p, :) = normal(j, :)
      normal(j, :) = pivot_row
      do i = j + 1, n
        normal(i, :) = normal(i, :) - normal(i, j)/normal(j, j)*normal(j, :)
      end do
    end do
    do j = n, 1, -1
      c(j) = (normal(j, n + 1) - dot_product(normal(j, j + 1:n), c(j + 1:n)))/normal(j, j)
    end do
  end function least_squares

  !> The maxima of e over consecutive windows of `period` steps do not grow
  !> (up to slack relative plus floor_slack absolute).
  logical function cycle_maxima_decrease(e, period, slack, floor_slack) result(ok)
    real(dp), intent(in) :: e(:), period, slack, floor_slack
    integer :: window, low, high
    real(dp) :: previous, current
    ok = .true.
    previous = huge(1.0_dp)
    window = 0
    do
      low = ceiling(window*period) + 1
      high = floor((window + 1)*period) + 1
      if (high > size(e)) exit
      current = maxval(e(low:max(low, high)))
      if (current > previous*(1.0_dp + slack) + floor_slack) ok = .false.
      previous = current
      window = window + 1
    end do
  end function cycle_maxima_decrease

  !> The period elongation / amplitude decay table for doc/verification.md.
  subroutine print_table()
    integer :: j
    character(len=160) :: line
    print '(a)', 'Wilson-theta, theta = 1.4: period elongation PE and amplitude decay per cycle AD'
    print '(a)', '   dt/T    rho(A)       PE (A)       PE (run)      AD (A)       AD (run)'// &
                 '   |u error|  |PE diff|  |AD diff|  max E/E0'
    do j = 1, size(rows)
      associate (r => rows(j))
      if (r%oscillating) then
        if (r%measured) then
          write(line, '(f7.2, 5es13.5, 3es11.2, f10.4)') r%ratio, real(r%radius, dp), real(r%pe, dp), &
            real(r%pe_measured, dp), real(r%ad, dp), real(r%ad_measured, dp), r%history_error, &
            real(r%pe_difference, dp), real(r%ad_difference, dp), 1.0_dp + r%overshoot
        else
          write(line, '(f7.2, 2es13.5, a13, es13.5, a13)') r%ratio, real(r%radius, dp), real(r%pe, dp), &
            'n/a', real(r%ad, dp), 'n/a'
        end if
      else if (r%ran .and. r%measured) then
        write(line, '(f7.2, es13.5, a, f10.6, a, f10.6, a)') r%ratio, real(r%radius, dp), &
          '   real roots: dominant ', real(r%dominant, dp), ' (A), ', real(r%dominant_measured, dp), ' (run)'
      else
        write(line, '(f7.2, es13.5, a, f10.6, a, f8.2)') r%ratio, real(r%radius, dp), &
          '   real roots: dominant ', real(r%dominant, dp), ' (A); no run (see NOTE), max E/E0 ', &
          1.0_dp + r%overshoot
      end if
      print '(a)', trim(line)
      end associate
    end do
  end subroutine print_table

  !> Second-order accuracy: PE ~ (dt/T)^2, AD ~ (dt/T)^3 at small dt/T,
  !> measured from the program (0.01 and 0.02) and from A alone at 1e-4.
  subroutine test_orders()
    real(qp) :: order_pe, order_ad, pe(2), ad(2), ratio, pe_decade(0:3), ad_decade(0:3)
    type(spectrum_t) :: s
    integer :: j
    logical :: decades_ok
    ! The next term of each expansion is O((omega dt)^2) relative: at
    ! dt/T = 0.02, (2 pi 0.02)^2 = 0.016, so the observed order may differ
    ! from 2 (3) by a few 0.01: 0.05. At 1e-4 that term is 4e-7: 1e-5.
    if (rows(1)%measured .and. rows(2)%measured) then
      order_pe = log(rows(2)%pe_measured/rows(1)%pe_measured)/log(rows(2)%ratio/rows(1)%ratio)
      order_ad = log(rows(2)%ad_measured/rows(1)%ad_measured)/log(rows(2)%ratio/rows(1)%ratio)
      print '(a, f8.4, a, f8.4)', 'observed orders from the runs (dt/T = 0.01, 0.02): PE ', real(order_pe, dp), &
        ', AD ', real(order_ad, dp)
      call check_close('observed order of PE from the runs = 2', real(order_pe, dp), 2.0_dp, 0.0_dp, 0.05_dp)
      call check_close('observed order of AD from the runs = 3', real(order_ad, dp), 3.0_dp, 0.0_dp, 0.05_dp)
    else
      call check('PE/AD measured at dt/T = 0.01 and 0.02', .false.)
    end if
    do j = 1, 2
      ratio = 1.0e-4_qp*j
      s = spectrum_of(amplification_at(ratio, real(theta_usual, qp)))
      call elongation_decay(ratio, s%modulus, s%phase, pe(j), ad(j))
    end do
    order_pe = log(pe(2)/pe(1))/log(2.0_qp)
    order_ad = log(ad(2)/ad(1))/log(2.0_qp)
    print '(a, f12.8, a, f12.8)', 'orders of A at dt/T = 1e-4, 2e-4: PE ', real(order_pe, dp), ', AD ', &
      real(order_ad, dp)
    call check_close('order of PE of A at dt/T -> 0 = 2', real(order_pe, dp), 2.0_dp, 0.0_dp, 1.0e-5_dp)
    call check_close('order of AD of A at dt/T -> 0 = 3', real(order_ad, dp), 3.0_dp, 0.0_dp, 1.0e-5_dp)
    ! PE, AD -> 0: positive and falling by ~100 (PE) and ~1000 (AD) per decade
    ! of dt/T from 1e-2 on (at 0.1 the higher-order terms still matter).
    decades_ok = .true.
    do j = 0, 3
      ratio = 10.0_qp**(-j - 2)
      s = spectrum_of(amplification_at(ratio, real(theta_usual, qp)))
      call elongation_decay(ratio, s%modulus, s%phase, pe_decade(j), ad_decade(j))
      if (pe_decade(j) <= 0.0_qp .or. ad_decade(j) <= 0.0_qp) decades_ok = .false.
      if (j > 0) then
        if (pe_decade(j - 1)/pe_decade(j) < 90.0_qp .or. ad_decade(j - 1)/ad_decade(j) < 900.0_qp) &
          decades_ok = .false.
      end if
    end do
    print '(a, 4es12.4)', 'PE of A at dt/T = 1e-2 .. 1e-5: ', real(pe_decade, dp)
    print '(a, 4es12.4)', 'AD of A at dt/T = 1e-2 .. 1e-5: ', real(ad_decade, dp)
    call check('PE, AD -> 0 as dt/T -> 0: > 0 and falling >= 90x (PE), >= 900x (AD) per decade', decades_ok)
  end subroutine test_orders

  !> rho(A) <= 1 for every dt/T at theta = 1.4 (and at the 1.37 the deck
  !> reader calls unconditionally stable); for theta = 1 the limit dt/T = sqrt(3)/pi.
  subroutine test_stability()
    real(qp) :: ratio, worst(2), low, high, middle, limit, split
    type(spectrum_t) :: s, s2
    integer :: k, iteration
    real(qp), parameter :: thetas(2) = [1.4_qp, 1.37_qp]
    ! 1e-4 <= dt/T <= 1e4, 20 per decade; the roots are exact to 1e-30, so
    ! rho <= 1 + 1e-25 is "<= 1".
    do iteration = 1, 2
      worst(iteration) = 0.0_qp
      do k = -80, 80
        ratio = 10.0_qp**(k/20.0_qp)
        s = spectrum_of(amplification_at(ratio, thetas(iteration)))
        worst(iteration) = max(worst(iteration), s%radius)
      end do
    end do
    call check('theta = 1.4: rho(A) <= 1 for 1e-4 <= dt/T <= 1e4', worst(1) <= 1.0_qp + 1.0e-25_qp, &
               'max rho '//trim(qtoa(worst(1))))
    call check('theta = 1.37: rho(A) <= 1 for 1e-4 <= dt/T <= 1e4', worst(2) <= 1.0_qp + 1.0e-25_qp, &
               'max rho '//trim(qtoa(worst(2))))
    call check('theta = 1.4: rho(A) < 1 at every table dt/T', all(rows%radius < 1.0_qp))

    ! theta = 1 (the linear acceleration method): undamped (rho = 1) below
    ! the limit, a real root below -1 above it. Bisection on rho > 1 + 1e-12:
    ! beyond the limit rho - 1 grows like sqrt(dt/T - limit), so the threshold
    ! moves the limit by ~1e-24 only.
    s = spectrum_of(amplification_at(0.55_qp, 1.0_qp))
    call check('theta = 1, dt/T = 0.55: rho(A) = 1 (undamped, stable)', abs(s%radius - 1.0_qp) < 1.0e-25_qp, &
               'rho '//trim(qtoa(s%radius)))
    s = spectrum_of(amplification_at(0.552_qp, 1.0_qp))
    call check('theta = 1, dt/T = 0.552: rho(A) > 1 (unstable)', s%radius > 1.0_qp + 1.0e-3_qp, &
               'rho '//trim(qtoa(s%radius)))
    low = 0.3_qp
    high = 1.0_qp
    do iteration = 1, 200
      middle = 0.5_qp*(low + high)
      if (middle <= low .or. middle >= high) exit
      s = spectrum_of(amplification_at(middle, 1.0_qp))
      if (s%radius > 1.0_qp + 1.0e-12_qp) then
        high = middle
      else
        low = middle
      end if
    end do
    limit = 0.5_qp*(low + high)
    print '(a, f22.18, a, f22.18)', 'theta = 1 stability limit by bisection: dt/T = ', real(limit, dp), &
      ';  sqrt(3)/pi = ', real(sqrt(3.0_qp)/pi_qp, dp)
    call check('theta = 1: stability limit by bisection = sqrt(3)/pi to 1e-15', &
               abs(limit - sqrt(3.0_qp)/pi_qp) < 1.0e-15_qp, 'limit '//trim(qtoa(limit)))
    ! theta = 1.4: where the principal pair turns into two real roots (the
    ! table's largest steps). Bisection on the oscillating flag, for doc/verification.md.
    low = 2.0_qp
    high = 5.0_qp
    do iteration = 1, 200
      middle = 0.5_qp*(low + high)
      if (middle <= low .or. middle >= high) exit
      s = spectrum_of(amplification_at(middle, real(theta_usual, qp)))
      if (s%oscillating) then
        low = middle
      else
        high = middle
      end if
    end do
    split = 0.5_qp*(low + high)
    print '(a, f12.6)', 'theta = 1.4: the principal roots are a complex pair up to dt/T = ', real(split, dp)
    s = spectrum_of(amplification_at(2.0_qp, 1.4_qp))
    s2 = spectrum_of(amplification_at(5.0_qp, 1.4_qp))
    call check('theta = 1.4: principal roots complex at dt/T = 2, real at 5', s%oscillating .and. &
               .not. s2%oscillating)
  end subroutine test_stability

  !> The program with WILSON THETA=1: follows A(theta = 1) below the limit
  !> (undamped) and stops as unstable above it.
  subroutine test_linear_acceleration_program()
    character(*), parameter :: path_stable = folder//'/sdof_theta1_stable.inp', &
                               path_unstable = folder//'/sdof_theta1_unstable.inp'
    integer, parameter :: steps = 300
    type(deck_t) :: deck
    type(record_t) :: record, unstable_record
    type(error_t), allocatable :: error
    real(qp) :: a(3, 3), x(3), worst, scale, c1, c0
    real(dp) :: period
    real(dp), allocatable :: u(:)
    integer :: n
    period = 2.0_dp*acos(-1.0_dp)/sqrt(real(omega2, dp))
    call write_sdof_deck(path_stable, 0.5_dp*period, steps, 1.0_dp)
    call read_deck(path_stable, deck, error)
    if (.not. allocated(error)) call solve_dynamic(deck, record, error)
    if (allocated(error)) then
      call check('theta = 1, dt/T = 0.5: runs', .false., error_text(error)); return
    end if
    a = amplification(omega2, real(deck%stages(1)%dt, qp), 1.0_qp)
    x = [0.0_qp, real(deck%dynamics%velocity(2), qp), 0.0_qp]
    u = sdof_displacement(record)
    if (size(u) /= steps + 1) then
      call check('theta = 1, dt/T = 0.5: history has every step', .false.); return
    end if
    worst = 0.0_qp
    scale = 0.0_qp
    do n = 1, steps
      x = matmul(a, x)
      worst = max(worst, abs(real(u(n + 1), qp) - x(1)))
      scale = max(scale, abs(x(1)))
    end do
    call check('theta = 1, dt/T = 0.5: u_n = e1^T A^n x0 within 20 n eps', worst/scale <= 20.0_dp*steps*eps, &
               'error '//trim(qtoa(worst/scale)))
    ! Undamped: the modulus measured from the series (its third root is 0, so
    ! the recurrence holds from the first steps on) is 1, to the error of the
    ! series times the fit's conditioning (phi = 2.1 here: ~1): 1e-10.
    call fit_recurrence(real(u(3:), qp), c1, c0)
    call check_close('theta = 1, dt/T = 0.5: measured modulus r = 1 (no amplitude decay)', &
                     real(sqrt(-c0), dp), 1.0_dp, 1.0e-10_dp)

    call write_sdof_deck(path_unstable, 0.6_dp*period, steps, 1.0_dp)
    call read_deck(path_unstable, deck, error)
    if (allocated(error)) then
      call check('theta = 1, dt/T = 0.6: deck reads', .false., error_text(error)); return
    end if
    call solve_dynamic(deck, unstable_record, error)
    call check('theta = 1, dt/T = 0.6 (above sqrt(3)/pi): the run stops as unstable', allocated(error))
    if (allocated(error)) call check('theta = 1, dt/T = 0.6: the message advises THETA >= 1.37', &
      index(error_text(error), 'unstable') > 0 .and. index(error_text(error), '1.37') > 0, error_text(error))
  end subroutine test_linear_acceleration_program

  ! ------------------------------------------------------------ free flight

  !> Checks a free-flight run against the closed form at every history row
  !> and snapshot. steps = the number of steps run (for the round-off models).
  subroutine check_free_flight(name, deck, record, steps)
    character(*), intent(in) :: name
    type(deck_t), intent(in) :: deck
    type(record_t), intent(in) :: record
    integer, intent(in) :: steps
    real(dp) :: v0, g, t, tau, mass, t_end, u_end, speed_max, tol_a, tol_v, tol_u, tol_e, tol_s
    real(dp) :: worst_u, worst_v, worst_a, worst_e, worst_w, worst_k, worst_node(6), worst_stress, h_min, path
    real(dp) :: kinetic_max
    real(dp), allocatable :: masses(:)
    integer :: row, j, node, col_t, col_u, col_v, col_a, col_k, col_b, col_g, col_s, col_x
    v0 = deck%dynamics%velocity(2)
    g = deck%loads%gravity
    tau = deck%dynamics%theta*minval(deck%stages%dt)
    masses = lumped_mass(deck%mesh, deck%settings, deck%materials)
    mass = whole_body_factor(deck%settings%geometry)*sum(masses(2::2))   ! the energies' basis: whole body
    col_t = history_index(record, 't_s')
    col_u = history_index(record, 'uz_cm_m')
    col_v = history_index(record, 'vz_cm_m_s')
    col_a = history_index(record, 'az_cm_m_s2')
    col_k = history_index(record, 'kinetic_J')
    col_s = history_index(record, 'strain_J')
    col_b = history_index(record, 'balance_error_J')
    col_g = history_index(record, 'gravity_work_J')
    col_x = history_index(record, 'external_work_J')
    t_end = deck%stages(size(deck%stages))%end_time
    u_end = abs(v0*t_end - 0.5_dp*g*t_end**2)
    speed_max = abs(v0) + g*t_end
    ! Round-off models (the motion itself is exact):
    ! - acceleration: eq. [37] subtracts terms of size 6|v|/tau and 3g, each
    !   rounded to a few eps; an error in a is multiplied by (1 - 1/theta) at
    !   the next step, so it does not accumulate: 20 eps (6|v|/tau + 3g);
    ! - velocity: each step adds a rounded a dt + dt/2 da (eq. [38]) and the
    !   sum is rounded: a few eps |v| per step, accumulated: 10 n eps |v|max;
    ! - displacement: the same for u (eq. [39]) plus the velocity error
    !   integrated over the run: 10 n eps (|u|max + |v|max t_end);
    ! - energies: kinetic, gravity work and the balance are sums of the same
    !   rounded quantities: 10 n eps times the largest kinetic energy.
    kinetic_max = 0.5_dp*mass*speed_max**2
    tol_a = 20.0_dp*eps*(6.0_dp*speed_max/tau + 3.0_dp*g)
    tol_v = 10.0_dp*steps*eps*speed_max
    tol_u = 10.0_dp*steps*eps*(u_end + speed_max*t_end)
    tol_e = 10.0_dp*steps*eps*kinetic_max
    worst_u = 0.0_dp
    worst_v = 0.0_dp
    worst_a = 0.0_dp
    worst_e = 0.0_dp
    worst_w = 0.0_dp
    worst_k = 0.0_dp
    do row = 1, record%nrow
      t = record%history(col_t, row)
      worst_u = max(worst_u, abs(record%history(col_u, row) - (v0*t - 0.5_dp*g*t**2)))
      worst_v = max(worst_v, abs(record%history(col_v, row) - (v0 - g*t)))
      worst_a = max(worst_a, abs(record%history(col_a, row) + g))
      worst_e = max(worst_e, abs(record%history(col_b, row)))
      ! gravity work = m g (distance fallen), distance = -(V t - g t^2/2)
      worst_w = max(worst_w, abs(record%history(col_g, row) + mass*g*(v0*t - 0.5_dp*g*t**2)))
      worst_k = max(worst_k, abs(record%history(col_k, row) - 0.5_dp*mass*(v0 - g*t)**2))
    end do
    print '(a, 4(es10.2, a))', name//': worst |error| / tolerance: uz_cm ', worst_u/tol_u, ', vz_cm ', &
      worst_v/tol_v, ', az_cm ', worst_a/tol_a, ', balance ', worst_e/tol_e, ' (1 = at the tolerance)'
    call check(name//': history rows up to TEND', record%nrow >= 2 .and. &
               abs(record%history(col_t, record%nrow) - t_end) <= 4.0_dp*eps*t_end)
    call check(name//': uz_cm = V t - g t^2/2 at every row within 10 n eps (|u| + |v| t)', worst_u <= tol_u, &
               'error '//trim(qtoa(real(worst_u, qp)))//' > '//trim(qtoa(real(tol_u, qp))))
    call check(name//': vz_cm = V - g t at every row within 10 n eps |v|', worst_v <= tol_v, &
               'error '//trim(qtoa(real(worst_v, qp)))//' > '//trim(qtoa(real(tol_v, qp))))
    call check(name//': az_cm = -g at every row within 20 eps (6|v|/tau + 3g)', worst_a <= tol_a, &
               'error '//trim(qtoa(real(worst_a, qp)))//' > '//trim(qtoa(real(tol_a, qp))))
    call check(name//': energy balance closes at every row within 10 n eps E_kin,max', worst_e <= tol_e, &
               'error '//trim(qtoa(real(worst_e, qp)))//' > '//trim(qtoa(real(tol_e, qp))))
    call check(name//': gravity_work = m g (distance fallen) at every row', worst_w <= tol_e, &
               'error '//trim(qtoa(real(worst_w, qp)))//' > '//trim(qtoa(real(tol_e, qp))))
    call check(name//': kinetic = m (V - g t)^2/2 at every row', worst_k <= tol_e, &
               'error '//trim(qtoa(real(worst_k, qp)))//' > '//trim(qtoa(real(tol_e, qp))))
    call check(name//': no external work (no loads, no supports)', all(record%history(col_x, 1:record%nrow) == 0.0_dp))
    call check_close(name//': summary gravity_work_J = m g (distance fallen)', real_summary(record, 'gravity_work_J'), &
                     -mass*g*(v0*t_end - 0.5_dp*g*t_end**2), 1.0e-9_dp)   ! 10 printed digits
    call check(name//': summary balance_error_max_rel within 10 n eps', &
               real_summary(record, 'balance_error_max_rel') <= 10.0_dp*steps*eps)

    ! Every node moves alike (rigid motion), at every snapshot: u and v carry
    ! the round-off of the centre of mass; a node's acceleration also the
    ! rounding of the solve of eq. [34], whose rows scale with lumped masses
    ! that differ ~100-fold (small near the axis) where the mass-weighted
    ! mean averages it out: 5 times the centre-of-mass tolerance.
    worst_node = 0.0_dp
    worst_stress = 0.0_dp
    do j = 1, size(record%snapshots)
      associate (snap => record%snapshots(j))
      t = snap%time
      do node = 1, deck%mesh%nnode
        worst_node = max(worst_node, [abs(snap%displacement(2, node) - (v0*t - 0.5_dp*g*t**2))/tol_u, &
                         abs(snap%displacement(1, node))/tol_u, &
                         abs(snap%velocity(2, node) - (v0 - g*t))/tol_v, abs(snap%velocity(1, node))/tol_v, &
                         abs(snap%acceleration(2, node) + g)/(5.0_dp*tol_a), &
                         abs(snap%acceleration(1, node))/(5.0_dp*tol_a)])
      end do
      worst_stress = max(worst_stress, maxval(abs(snap%stress_gauss)), maxval(abs(snap%stress)))
      end associate
    end do
    call check(name//': every node: u, v, a = the centre of mass motion (u_r = 0) at '// &
               integer_text(size(record%snapshots))//' snapshots', all(worst_node <= 1.0_dp), &
               'worst error / tolerance (uz, ur, vz, vr, az, ar) '//trim(qtoa(real(worst_node(1), qp)))// &
               trim(qtoa(real(worst_node(2), qp)))//trim(qtoa(real(worst_node(3), qp)))// &
               trim(qtoa(real(worst_node(4), qp)))//trim(qtoa(real(worst_node(5), qp)))// &
               trim(qtoa(real(worst_node(6), qp))))
    ! Stresses: a rigid translation du gives strains sum_a dN_a/dz du that
    ! cancel to eps |du|/h_min per step; summed over the path the strain is
    ! below eps (path length)/h_min, the stress below M_c times that. 100 for
    ! the ~8 terms of B du and the averaging. (For this deck that is ~1e-7 Pa,
    ! against E = 1.8e7 Pa: E * 1e-14.)
    h_min = smallest_edge(deck)
    path = abs(v0)*t_end + 0.5_dp*g*t_end**2
    tol_s = 100.0_dp*eps*path/h_min*(deck%materials(1)%bulk + 4.0_dp*deck%materials(1)%shear/3.0_dp)
    print '(a, es10.2, a, es10.2, a)', name//': max |stress| ', worst_stress, ' Pa = ', &
      worst_stress/deck%materials(1)%young, ' E'
    call check(name//': all stresses are round-off (< 100 eps M_c path/h_min = '// &
               trim(qtoa(real(tol_s, qp)))//' Pa)', worst_stress <= tol_s, &
               'max |sigma| '//trim(qtoa(real(worst_stress, qp))))
    call check(name//': strain energy round-off', maxval(abs(record%history(col_s, 1:record%nrow))) <= tol_e)
  end subroutine check_free_flight

  real(dp) function real_summary(record, key) result(value)
    type(record_t), intent(in) :: record
    character(*), intent(in) :: key
    character(:), allocatable :: text
    integer :: ios
    text = summary_value(record, key)
    read(text, *, iostat=ios) value
    if (ios /= 0) value = huge(1.0_dp)
  end function real_summary

  !> Shortest element edge of the mesh.
  real(dp) function smallest_edge(deck) result(h)
    type(deck_t), intent(in) :: deck
    integer :: e, j
    h = huge(1.0_dp)
    do e = 1, deck%mesh%nelem
      do j = 1, 4
        h = min(h, norm2(deck%mesh%xy(:, deck%mesh%connectivity(j, e)) - &
                         deck%mesh%xy(:, deck%mesh%connectivity(mod(j, 4) + 1, e))))
      end do
    end do
  end function smallest_edge

  !> inputs/free_flight.inp end to end: the solver's record, and run_deck's EXPECT checks.
  subroutine test_free_flight_deck()
    character(*), parameter :: path = 'inputs/free_flight.inp'
    type(deck_t) :: deck
    type(record_t) :: record
    type(error_t), allocatable :: error
    character(len=24), parameter :: keys(4) = [character(len=24) :: 'uz_cm_m', 'vz_cm_m_s', 'az_cm_m_s2', &
                                                'probe_bottom_uz_m']
    integer :: k
    call read_deck(path, deck, error)
    if (allocated(error)) then
      call check('free_flight deck reads', .false., error_text(error)); return
    end if
    call check('free_flight: no supports, no warnings', size(deck%loads%fixes) == 0 .and. size(deck%warnings) == 0)
    call solve_dynamic(deck, record, error)
    if (allocated(error)) then
      call check('free_flight runs', .false., error_text(error)); return
    end if
    call check('free_flight: one factorization', summary_value(record, 'factorizations') == '1')
    call check('free_flight: snapshots at 0, 1 ms and the end', size(record%snapshots) == 3)
    call check_free_flight('free_flight', deck, record, deck%stages(1)%steps)
    call run_deck(path, folder//'/out', record, error)
    if (allocated(error)) then
      call check('free_flight through run_deck', .false., error_text(error)); return
    end if
    do k = 1, size(keys)
      call check('free_flight: EXPECT '//trim(keys(k))//' within RTOL', &
                 summary_value(record, 'expect_'//trim(keys(k))//'_within_rtol') == 'yes', &
                 'rel. error '//summary_value(record, 'expect_'//trim(keys(k))//'_rel_error'))
    end do
  end subroutine test_free_flight_deck

  !> The same flight with two TIME stages of different steps (one
  !> factorization each): still exact.
  subroutine test_free_flight_two_stages()
    character(*), parameter :: path = folder//'/free_flight_two_stages.inp'
    type(deck_t) :: deck
    type(record_t) :: record
    type(error_t), allocatable :: error
    call write_deck(path, [character(len=200) :: &
      'TITLE Free flight, two time stages', 'ANALYSIS DYNAMIC', 'GEOMETRY AXISYMMETRIC', &
      'MATERIAL apple ELASTIC E=18.11e6 NU=0.219 RHO=756.85', 'MESH SPHERE R=0.0366 LEVEL=1', &
      'INITIAL VZ=-0.9982', 'GRAVITY G=9.8', &
      'TIME DT=1e-5 TEND=1e-3', 'TIME DT=3e-5 TEND=2e-3', &   ! 100 steps, then 34 steps of 2.94e-5 s
      'OUTPUT EVERY=1 FIELDS=5e-4,1.5e-3', 'END'])
    call read_deck(path, deck, error)
    if (allocated(error)) then
      call check('free_flight two stages: deck reads', .false., error_text(error)); return
    end if
    call check('free_flight two stages: 100 + 34 steps', all(deck%stages%steps == [100, 34]))
    call solve_dynamic(deck, record, error)
    if (allocated(error)) then
      call check('free_flight two stages runs', .false., error_text(error)); return
    end if
    call check('free_flight two stages: factorizations = 2', summary_value(record, 'factorizations') == '2', &
               'factorizations = '//summary_value(record, 'factorizations'))
    call check_free_flight('free_flight two stages', deck, record, sum(deck%stages%steps))
  end subroutine test_free_flight_two_stages

  !> 1e5 steps of a one-element version (a short cylinder, axisymmetric):
  !> the round-off models grow with n, the motion stays exact.
  subroutine test_free_flight_long_run()
    character(*), parameter :: path = folder//'/free_flight_long.inp'
    type(deck_t) :: deck
    type(record_t) :: record
    type(error_t), allocatable :: error
    call write_deck(path, [character(len=200) :: &
      'TITLE Free flight, one element, 1e5 steps', 'ANALYSIS DYNAMIC', 'GEOMETRY AXISYMMETRIC', &
      'MATERIAL apple ELASTIC E=18.11e6 NU=0.219 RHO=756.85', &
      'NODE 1 0 0', 'NODE 2 0.0366 0', 'NODE 3 0.0366 0.0732', 'NODE 4 0 0.0732', 'ELEMENT 1 1 2 3 4', &
      'INITIAL VZ=-0.9982', 'GRAVITY G=9.8', 'TIME DT=1e-5 TEND=1', 'OUTPUT EVERY=1000 FIELDS=0.5', 'END'])
    call read_deck(path, deck, error)
    if (allocated(error)) then
      call check('free_flight long run: deck reads', .false., error_text(error)); return
    end if
    call check('free_flight long run: 1e5 steps', deck%stages(1)%steps == 100000)
    call solve_dynamic(deck, record, error)
    if (allocated(error)) then
      call check('free_flight long run runs', .false., error_text(error)); return
    end if
    call check_free_flight('free_flight long run', deck, record, deck%stages(1)%steps)
  end subroutine test_free_flight_long_run
end program test_wilson
