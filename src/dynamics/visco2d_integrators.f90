!> The time integrators as data: one row of coefficients per sub-step, and the
!> pure coefficient algebra of the step (eqs. [34]-[42] generalized).
!>
!> A collocation row (theta, beta, gamma, alpha_m, alpha_f) solves over
!> h = theta dt for dU = u(t + h) - u(t), with a Newmark acceleration
!>   a_h = (dU - h v - h^2 (1/2 - beta) a)/(beta h^2),
!> an effective stiffness (1 - alpha_f) S_h + (1 - alpha_m)/(beta h^2) M (eq. [35]),
!> the mass part M [(1 - alpha_m)(v/(beta h) + (1/(2 beta) - 1) a) - alpha_m a]
!> of the effective load (eq. [36]), and the update to t + dt
!>   a+ = a + (a_h - a)/theta                        eq. [37]
!>   v+ = v + dt ((1 - gamma) a + gamma a+)           eq. [38]
!>   u+ = u + dt v + dt^2 ((1/2 - beta) a + beta a+)  eq. [39]
!> (u+ = u + dU exactly when theta = 1). The paper's Wilson-theta is the row
!> (theta, 1/6, 1/2, 0, 0); NEWMARK (1, beta, gamma, 0, 0); HHT (1,
!> (1 + alpha)^2/4, 1/2 + alpha, 0, alpha); GENERALIZED_ALPHA (Chung and
!> Hulbert 1993) from rho_inf. BATHE (Bathe and Baig 2005) is two rows over
!> dt/2 each: the trapezoidal rule (Newmark 1/4, 1/2), then the 3-point
!> backward Euler row, whose velocity and acceleration use the states at t
!> and t + dt/2:
!>   v+ = (u_t - 4 u_{t+dt/2} + 3 u+)/dt,  a+ = (v_t - 4 v_{t+dt/2} + 3 v+)/dt.
!>
!> Wilson's arithmetic is kept exactly as the paper's code had it (1/beta = 6
!> stored, no alpha terms when they are 0), so its results are bit-identical.
module visco2d_integrators
  use visco2d_kinds, only: dp
  use visco2d_strings, only: short_real
  use visco2d_dynamic_cards, only: dynamic_settings_t, theta_unconditional, integrator_wilson, integrator_newmark, &
                                   integrator_hht, integrator_generalized_alpha, integrator_bathe, integrator_names
  implicit none
  private

  public :: integrator_t, substep_t, integrator_create, rule_collocation, rule_backward_euler
  public :: solve_interval, mass_coefficient, inertia_load, solve_point_inertia, update_kinematics
  public :: energy_overshoot, stability_advice

  integer, parameter :: rule_collocation = 1       !< Newmark / Wilson-theta / alpha row
  integer, parameter :: rule_backward_euler = 2    !< Bathe's 3-point backward Euler sub-step

  !> One sub-step: its rule, its share of dt and its coefficients.
  type :: substep_t
    integer :: rule = rule_collocation
    real(dp) :: fraction = 1.0_dp        !< the sub-step's share of dt
    real(dp) :: theta = 1.0_dp           !< collocation factor: the solve point is t + theta (fraction dt)
    real(dp) :: inverse_beta = 4.0_dp    !< 1/beta (6 exactly for Wilson-theta)
    real(dp) :: gamma = 0.5_dp
    real(dp) :: alpha_m = 0.0_dp         !< inertia taken at t + (1 - alpha_m) dt
    real(dp) :: alpha_f = 0.0_dp         !< stiffness and loads taken at t + (1 - alpha_f) dt
  end type substep_t

  !> An integrator: its kind (an integrator_* of visco2d_dynamic_cards), its
  !> label for the summary, and its sub-steps.
  type :: integrator_t
    integer :: kind = integrator_wilson
    character(:), allocatable :: label
    type(substep_t), allocatable :: rows(:)
    real(dp) :: theta = 1.4_dp, beta = 1.0_dp/6.0_dp, gamma = 0.5_dp   !< as given (for the advice)
  end type integrator_t

contains

  !> The integrator of the INTEGRATOR (or WILSON) card.
  function integrator_create(dynamics) result(integrator)
    type(dynamic_settings_t), intent(in) :: dynamics
    type(integrator_t) :: integrator
    real(dp) :: alpha_m, alpha_f, rho
    integrator%kind = dynamics%integrator
    integrator%label = trim(integrator_names(dynamics%integrator))
    select case (dynamics%integrator)
    case (integrator_wilson)
      integrator%rows = [substep_t(rule_collocation, 1.0_dp, dynamics%theta, 6.0_dp, 0.5_dp, 0.0_dp, 0.0_dp)]
      integrator%label = integrator%label//' THETA='//short_real(dynamics%theta)
      integrator%theta = dynamics%theta
    case (integrator_newmark)
      integrator%rows = [substep_t(rule_collocation, 1.0_dp, 1.0_dp, 1.0_dp/dynamics%beta, dynamics%gamma, 0.0_dp, 0.0_dp)]
      integrator%label = integrator%label//' BETA='//short_real(dynamics%beta)//' GAMMA='//short_real(dynamics%gamma)
      integrator%beta = dynamics%beta
      integrator%gamma = dynamics%gamma
    case (integrator_hht)
      alpha_f = dynamics%alpha
      integrator%rows = [substep_t(rule_collocation, 1.0_dp, 1.0_dp, 4.0_dp/(1.0_dp + alpha_f)**2, 0.5_dp + alpha_f, &
                               0.0_dp, alpha_f)]
      integrator%label = integrator%label//' ALPHA='//short_real(dynamics%alpha)
    case (integrator_generalized_alpha)
      rho = dynamics%rho_infinity
      alpha_m = (2.0_dp*rho - 1.0_dp)/(rho + 1.0_dp)
      alpha_f = rho/(rho + 1.0_dp)
      integrator%rows = [substep_t(rule_collocation, 1.0_dp, 1.0_dp, 4.0_dp/(1.0_dp - alpha_m + alpha_f)**2, &
                               0.5_dp - alpha_m + alpha_f, alpha_m, alpha_f)]
      integrator%label = integrator%label//' RHO_INF='//short_real(rho)
    case (integrator_bathe)
      integrator%rows = [substep_t(rule_collocation, 0.5_dp, 1.0_dp, 4.0_dp, 0.5_dp, 0.0_dp, 0.0_dp), &
                         substep_t(rule_backward_euler, 0.5_dp, 1.0_dp, 4.0_dp, 0.5_dp, 0.0_dp, 0.0_dp)]
    end select
  end function integrator_create

  !> The solve interval h of a row over a sub-step of length `length`
  !> (theta dt for Wilson-theta, the sub-step itself otherwise).
  pure real(dp) function solve_interval(row, length) result(h)
    type(substep_t), intent(in) :: row
    real(dp), intent(in) :: length
    h = row%theta*length
  end function solve_interval

  !> The effective-mass coefficient c of eq. [35], S~ = (1 - alpha_f) S_h + c M:
  !> (1 - alpha_m)/(beta h^2) (6/tau^2 for Wilson-theta); 9/dt^2 = 9/(2 h)^2
  !> for the backward Euler sub-step (h = dt/2).
  pure real(dp) function mass_coefficient(row, h) result(c)
    type(substep_t), intent(in) :: row
    real(dp), intent(in) :: h
    if (row%rule == rule_backward_euler) then
      c = 9.0_dp/(2.0_dp*h)**2
    else
      c = row%inverse_beta/h**2
      if (row%alpha_m /= 0.0_dp) c = (1.0_dp - row%alpha_m)*c
    end if
  end function mass_coefficient

  !> The mass part b of the effective load (eq. [36]: R~ = ... + M b) from the
  !> state (u, v, a) at the sub-step's start; for backward Euler also the
  !> state (u0, v0) at the start of the whole step:
  !>   collocation  b = (1 - alpha_m)(v/(beta h) + (1/(2 beta) - 1) a) - alpha_m a   (6/tau v + 2 a for Wilson)
  !>   backward Euler  b = -(3 (u0 - u)/dt^2 + (v0 - 4 v)/dt), dt = 2 h.
  pure function inertia_load(row, h, u, v, a, u0, v0) result(b)
    type(substep_t), intent(in) :: row
    real(dp), intent(in) :: h
    real(dp), intent(in) :: u(:), v(:), a(:), u0(:), v0(:)
    real(dp) :: b(size(v))
    if (row%rule == rule_backward_euler) then
      b = -(3.0_dp*(u0 - u)/(2.0_dp*h)**2 + (v0 - 4.0_dp*v)/(2.0_dp*h))
    else if (row%alpha_m == 0.0_dp) then
      b = row%inverse_beta/h*v + (0.5_dp*row%inverse_beta - 1.0_dp)*a
    else
      b = (1.0_dp - row%alpha_m)*(row%inverse_beta/h*v + (0.5_dp*row%inverse_beta - 1.0_dp)*a) - row%alpha_m*a
    end if
  end function inertia_load

  !> The acceleration the effective system holds the mass to at the solve
  !> point, from the solution dU: M times it is the inertia part of S~ dU - R~.
  !>   collocation  (1 - alpha_m) a_h + alpha_m a   (a_h = 6/tau^2 dU - 6/tau v - 2 a for Wilson)
  !>   backward Euler  a+ = 9/dt^2 dU - b.
  pure function solve_point_inertia(row, h, du, u, v, a, u0, v0) result(inertia)
    type(substep_t), intent(in) :: row
    real(dp), intent(in) :: h
    real(dp), intent(in) :: du(:), u(:), v(:), a(:), u0(:), v0(:)
    real(dp) :: inertia(size(du))
    if (row%rule == rule_backward_euler) then
      inertia = mass_coefficient(row, h)*du - inertia_load(row, h, u, v, a, u0, v0)
    else if (row%alpha_m == 0.0_dp) then
      inertia = row%inverse_beta/h**2*du - row%inverse_beta/h*v - (0.5_dp*row%inverse_beta - 1.0_dp)*a
    else
      inertia = (1.0_dp - row%alpha_m)*(row%inverse_beta/h**2*du - row%inverse_beta/h*v - &
                                        (0.5_dp*row%inverse_beta - 1.0_dp)*a) + row%alpha_m*a
    end if
  end function solve_point_inertia

  !> The increments over the sub-step of length `length` from the solution
  !> dU at the solve point (eqs. [37]-[39] generalized; the state at the
  !> sub-step's start (u, v, a), at the step's start (u0, v0) for backward Euler).
  pure subroutine update_kinematics(row, length, solution, u, v, a, u0, v0, du, dv, da)
    type(substep_t), intent(in) :: row
    real(dp), intent(in) :: length
    real(dp), intent(in) :: solution(:), u(:), v(:), a(:), u0(:), v0(:)
    real(dp), intent(out) :: du(:), dv(:), da(:)
    real(dp) :: h, dt
    h = solve_interval(row, length)
    if (row%rule == rule_backward_euler) then
      dt = 2.0_dp*length
      du = solution
      dv = (3.0_dp*solution + (u0 - u))/dt - v                                      ! v+ - v
      da = (v0 - 4.0_dp*v + 3.0_dp*(v + dv))/dt - a                                 ! a+ - a
      return
    end if
    da = (row%inverse_beta/h**2*solution - row%inverse_beta/h*v - 0.5_dp*row%inverse_beta*a)/row%theta  ! eq. [37]
    dv = a*length + row%gamma*length*da                                            ! eq. [38]
    if (row%theta == 1.0_dp) then
      du = solution                                                                ! eq. [39] at theta = 1
    else
      du = v*length + 0.5_dp*length**2*a + length**2/row%inverse_beta*da             ! eq. [39]
    end if
  end subroutine update_kinematics

  !> The factor by which the energy bound of the instability check is widened
  !> for a stable step's transient overshoot of a mode of frequency omega_max
  !> (the modes of the linear problem with the lumped mass are independent
  !> single degrees of freedom). Wilson-theta (theta >= 1.37, spectral radius
  !> < 1) can raise a mode's energy by about ((1 - 1/theta^2) omega dt)^2
  !> before it decays (the paper's method: kept as it always was). For the
  !> other integrators it is measured on the single degree of freedom with
  !> their own coefficient algebra (sdof_overshoot): none for the trapezoidal
  !> rule (NEWMARK 1/4, 1/2 conserves the energy of a linear system) and for
  !> BATHE; for HHT and GENERALIZED_ALPHA it grows as (c omega dt)^2 at large
  !> omega dt (c = 0.009 for ALPHA = 0.05, 0.02 for RHO_INF = 0.8).
  pure real(dp) function energy_overshoot(integrator, omega_max, dt) result(factor)
    type(integrator_t), intent(in) :: integrator
    real(dp), intent(in) :: omega_max, dt
    integer :: k
    if (integrator%kind == integrator_wilson) then
      factor = max(1.0_dp, 2.0_dp*((1.0_dp - 1.0_dp/integrator%theta**2)*omega_max*dt)**2)
      return
    end if
    factor = 1.0_dp
    do k = 0, 24                                      ! every mode from omega_max down by 2^24
      factor = max(factor, sdof_overshoot(integrator, omega_max*dt/2.0_dp**k))
    end do
  end function energy_overshoot

  !> The largest energy ratio E_n/E_0 (E = (u^2 + v^2)/2, omega = 1) over the
  !> first 10 steps of a single degree of freedom at omega dt = `ratio`, from
  !> a unit displacement and from a unit velocity (each in equilibrium).
  pure real(dp) function sdof_overshoot(integrator, ratio) result(worst)
    type(integrator_t), intent(in) :: integrator
    real(dp), intent(in) :: ratio
    real(dp) :: u(1), v(1), a(1), u0(1), v0(1), du(1), dv(1), da(1), solution(1), h, length
    integer :: start, n, r
    worst = 1.0_dp
    if (.not. (ratio > 0.0_dp)) return
    do start = 1, 2
      u = merge(1.0_dp, 0.0_dp, start == 1)
      v = merge(0.0_dp, 1.0_dp, start == 1)
      a = -u
      do n = 1, 10
        u0 = u
        v0 = v
        do r = 1, size(integrator%rows)
          associate (row => integrator%rows(r))
          length = row%fraction*ratio
          h = solve_interval(row, length)
          solution = (-u + inertia_load(row, h, u, v, a, u0, v0))/((1.0_dp - row%alpha_f) + mass_coefficient(row, h))
          call update_kinematics(row, length, solution, u, v, a, u0, v0, du, dv, da)
          u = u + du
          v = v + dv
          a = a + da
          end associate
        end do
        worst = max(worst, u(1)**2 + v(1)**2)
      end do
    end do
  end function sdof_overshoot

  !> What to do about an unstable run, with the integrator's stability condition.
  function stability_advice(integrator) result(advice)
    type(integrator_t), intent(in) :: integrator
    character(:), allocatable :: advice
    advice = 'check the material constants, the loads and DT'
    select case (integrator%kind)
    case (integrator_wilson)
      if (integrator%theta < theta_unconditional) &
        advice = 'WILSON THETA = '//short_real(integrator%theta)//' is only conditionally stable: use THETA >= 1.37 '// &
          '(1.4 is usual) or a DT well below the shortest period of the mesh'
    case (integrator_newmark)
      if (2.0_dp*integrator%beta < integrator%gamma) &
        advice = 'NEWMARK BETA = '//short_real(integrator%beta)//', GAMMA = '//short_real(integrator%gamma)// &
          ' is only conditionally stable (2 BETA < GAMMA; stable for omega DT < 1/sqrt(GAMMA/2 - BETA) at the '// &
          'highest frequency omega of the mesh): use BETA >= GAMMA/2 (0.25, 0.5 is usual) or a smaller DT'
    case default
      advice = 'INTEGRATOR '//integrator%label//' is unconditionally stable for a linear problem: '//advice
    end select
  end function stability_advice
end module visco2d_integrators
