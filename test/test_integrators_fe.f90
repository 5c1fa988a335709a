!> The integrators of INTEGRATOR on the finite-element impacts of the paper
!> (inputs/table1_elastic.inp, elastic, and inputs/table2_viscoelastic.inp,
!> with viscoelastic memory): each runs to maximum deformation with finite
!> results and finds the same impact as the paper's Wilson-theta.
!>
!> Why the tolerances: the impact is a slow motion of the whole body (the
!> contact lasts about 3 ms, omega ~ pi/3 ms ~ 1e3 1/s) sampled at
!> DT = 0.01 ms, omega DT ~ 0.01. Every integrator here is second-order
!> accurate, with period errors of order (omega DT)^2/12 ~ 1e-5 on that
!> motion and algorithmic damping of order alpha omega DT ~ 1e-3 or less;
!> they differ mainly in how they treat the mesh's high modes (omega DT ~ 1),
!> which ring in the contact pressure but hardly move the centre of mass.
!> So alpha_max (an approach of the centre of mass) must agree within 1 %,
!> its time within 1 % plus two steps (the maximum is sampled at steps, and
!> a node-by-node contact arrest one step earlier or later moves it), and
!> the peak pressure q_max (a surface stress, ringing) within 5 %. Measured
!> differences are far smaller (alpha: 1e-5, q: 0.3 %); a wrong coefficient
!> (e.g. beta for 1/beta, a missing (1 - alpha_f)) changes alpha by far more.
program test_integrators_fe
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, error_text
  use visco2d_deck, only: deck_t, read_deck
  use visco2d_record, only: record_t
  use visco2d_expect, only: summary_value
  use visco2d_dynamic, only: solve_dynamic
  use visco2d_testing, only: check, check_close, test_summary, write_deck, summary_real, read_lines
  use visco2d_dynamic_cards, only: dynamic_settings_t, integrator_newmark, integrator_hht, integrator_bathe
  use visco2d_integrators, only: integrator_t, integrator_create, energy_overshoot
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none

  character(*), parameter :: folder = 'build/test-tmp/integrators_fe'
  character(len=40), parameter :: cards(5) = [character(len=40) :: 'WILSON THETA=1.4', 'INTEGRATOR NEWMARK', &
    'INTEGRATOR HHT ALPHA=0.05', 'INTEGRATOR GENERALIZED_ALPHA RHO_INF=0.8', 'INTEGRATOR BATHE']
  character(len=18), parameter :: labels(5) = [character(len=18) :: 'WILSON', 'NEWMARK', 'HHT', &
                                               'GENERALIZED_ALPHA', 'BATHE']

  call execute_command_line('mkdir -p '//folder)
  call impact_family('table1_elastic')
  call impact_family('table2_viscoelastic')
  call newmark_advice()
  call overshoot_factors()
  call test_summary('test_integrators_fe')

contains

  !> Each integrator on one paper deck, against the Wilson-theta run.
  subroutine impact_family(deck_name)
    character(*), intent(in) :: deck_name
    real(dp) :: alpha(5), t_alpha(5), q(5), dt
    integer :: k
    type(record_t) :: record
    logical :: ran
    do k = 1, size(cards)
      call run_with(deck_name, trim(cards(k)), record, ran, dt)
      if (.not. ran) then
        alpha(k) = huge(1.0_dp)
        t_alpha(k) = huge(1.0_dp)
        q(k) = huge(1.0_dp)
        cycle
      end if
      alpha(k) = summary_real(record, 'alpha_max_mm')
      t_alpha(k) = summary_real(record, 't_alpha_max_ms')
      q(k) = summary_real(record, 'q_max_MPa')
      call check(deck_name//' '//trim(labels(k))//': finite alpha, t, q', all(ieee_is_finite([alpha(k), t_alpha(k), &
                 q(k)])) .and. alpha(k) > 0.0_dp .and. t_alpha(k) > 0.0_dp .and. q(k) > 0.0_dp)
      if (k == 1) then
        call check(deck_name//' WILSON: theta key, no integrator key', len(summary_value(record, 'theta')) > 0 .and. &
                   len(summary_value(record, 'integrator')) == 0)
      else
        call check(deck_name//' '//trim(labels(k))//': integrator key names it', &
                   index(summary_value(record, 'integrator'), trim(labels(k))) == 1, summary_value(record, 'integrator'))
        call check_close(deck_name//' '//trim(labels(k))//': alpha_max within 1 % of Wilson-theta', alpha(k), &
                         alpha(1), rtol=0.01_dp)
        call check_close(deck_name//' '//trim(labels(k))//': t_alpha_max within 1 % + 2 steps of Wilson-theta', &
                         t_alpha(k), t_alpha(1), rtol=0.01_dp, atol=2.0e3_dp*dt)
        call check_close(deck_name//' '//trim(labels(k))//': q_max within 5 % of Wilson-theta', q(k), q(1), &
                         rtol=0.05_dp)
      end if
      if (k == 5) call check(deck_name//' BATHE: two effective stiffnesses (one per sub-step)', &
                             nint(summary_real(record, 'factorizations')) == 2)
    end do
  end subroutine impact_family

  !> NEWMARK with 2 BETA < GAMMA is only conditionally stable: far above
  !> its limit (omega DT < 1/sqrt(GAMMA/2 - BETA) = 2.6 for 0.1, 0.5; the
  !> Table 1 mesh has omega_max DT ~ 1 at DT = 0.01 ms, so DT = 0.5 ms is far
  !> beyond) the run stops with an error that names the integrator and its
  !> condition; the trapezoidal rule (unconditionally stable) runs the same deck.
  subroutine newmark_advice()
    type(record_t) :: record
    logical :: ran
    real(dp) :: dt
    character(:), allocatable :: message
    call run_with('table1_elastic', 'INTEGRATOR NEWMARK BETA=0.1 GAMMA=0.5', record, ran, dt, &
                  time_card='TIME DT=5e-4 TEND=0.1', free_flight=.true., message=message)
    call check('NEWMARK BETA=0.1: an unstable run stops with an error', .not. ran, message)
    print "(a)", "  (the error: "//message//")"
    call check('NEWMARK BETA=0.1: the advice names the integrator and its condition', &
               index(message, 'NEWMARK BETA = 0.1') > 0 .and. index(message, '2 BETA < GAMMA') > 0, message)
    call run_with('table1_elastic', 'INTEGRATOR NEWMARK', record, ran, dt, time_card='TIME DT=5e-4 TEND=0.1', &
                  free_flight=.true., message=message)
    call check('NEWMARK 0.25, 0.5: the same deck runs (unconditionally stable)', ran, message)
  end subroutine newmark_advice

  !> The widening of the instability bound (energy_overshoot), measured on a
  !> single degree of freedom: the trapezoidal rule conserves the energy of a
  !> linear oscillator (factor 1 to round-off at any omega dt); Bathe's
  !> method never raises it (factor 1 to round-off); HHT's first-step overshoot grows as
  !> (omega dt)^2 at large omega dt (ratio 100 from 1e3 to 1e4, within 1 %).
  subroutine overshoot_factors()
    type(dynamic_settings_t) :: dynamics
    type(integrator_t) :: integrator
    real(dp) :: large, larger
    dynamics%integrator = integrator_newmark
    integrator = integrator_create(dynamics)
    call check_close('overshoot NEWMARK 1/4, 1/2 at omega dt = 1e3: 1 (energy conserved)', &
                     energy_overshoot(integrator, 1.0e3_dp, 1.0_dp), 1.0_dp, rtol=1.0e-10_dp)
    dynamics%integrator = integrator_bathe
    integrator = integrator_create(dynamics)
    call check_close('overshoot BATHE at omega dt = 0.1: 1', energy_overshoot(integrator, 0.1_dp, 1.0_dp), 1.0_dp, &
                     rtol=1.0e-10_dp)
    call check_close('overshoot BATHE at omega dt = 1e5: 1', energy_overshoot(integrator, 1.0e5_dp, 1.0_dp), 1.0_dp, &
                     rtol=1.0e-10_dp)
    dynamics%integrator = integrator_hht
    integrator = integrator_create(dynamics)
    large = energy_overshoot(integrator, 1.0e3_dp, 1.0_dp)
    larger = energy_overshoot(integrator, 1.0e4_dp, 1.0_dp)
    call check('overshoot HHT 0.05 at omega dt = 1e3 above 1', large > 1.0_dp, exact_ratio(large))
    call check_close('overshoot HHT 0.05 grows as (omega dt)^2', larger/large, 100.0_dp, rtol=0.01_dp)
  end subroutine overshoot_factors

  !> A real for a detail.
  function exact_ratio(value) result(text)
    real(dp), intent(in) :: value
    character(len=24) :: text
    write(text, '(es24.16)') value
  end function exact_ratio

  !> Run inputs/<deck_name>.inp with its WILSON card replaced by `card`
  !> (optionally its TIME card, and without plate and stop: free flight).
  subroutine run_with(deck_name, card, record, ran, dt, time_card, free_flight, message)
    character(*), intent(in) :: deck_name, card
    type(record_t), intent(out) :: record
    logical, intent(out) :: ran
    real(dp), intent(out) :: dt
    character(*), intent(in), optional :: time_card
    logical, intent(in), optional :: free_flight
    character(:), allocatable, intent(out), optional :: message
    character(:), allocatable :: lines(:)
    character(len=256), allocatable :: out(:)
    character(:), allocatable :: path
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    logical :: found, skip
    integer :: k, n
    ran = .false.
    dt = 0.0_dp
    if (present(message)) message = ''
    call read_lines('inputs/'//deck_name//'.inp', lines, found)
    call check('read inputs/'//deck_name//'.inp', found)
    if (.not. found) return
    allocate(out(size(lines)))
    n = 0
    do k = 1, size(lines)
      skip = .false.
      if (present(free_flight)) skip = free_flight .and. (index(lines(k), 'PLATE') == 1 .or. index(lines(k), 'STOP') == 1)
      if (skip) cycle
      n = n + 1
      out(n) = lines(k)
      if (index(lines(k), 'WILSON') == 1) out(n) = card
      if (present(time_card) .and. index(lines(k), 'TIME') == 1) out(n) = time_card
    end do
    path = folder//'/'//deck_name//'.inp'
    call write_deck(path, out(:n))
    call read_deck(path, deck, error)
    if (.not. allocated(error)) then
      dt = deck%stages(1)%dt
      call solve_dynamic(deck, record, error)
    end if
    ran = .not. allocated(error)
    if (present(message) .and. allocated(error)) message = error_text(error)
    if (.not. present(message) .and. allocated(error)) call check(deck_name//' with '//card//' runs', .false., &
                                                                  error_text(error))
  end subroutine run_with
end program test_integrators_fe
