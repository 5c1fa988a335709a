!> The cards of the dynamic extension and of the scene around the body:
!> INTEGRATOR (and its legacy form WILSON), INITIAL, DROP, GRAVITY, OUTPUT and
!> FORMULATION. Each reader checks
!> its own card; visco2d_deck checks how the cards fit together.
module visco2d_dynamic_cards
  use visco2d_kinds, only: dp, formulation_standard, formulation_bbar
  use visco2d_error, only: error_t
  use visco2d_strings, only: short_real, integer_text
  use visco2d_ranges, only: speed_range, acceleration_range, drop_height_range, gravity_range, time_range, &
                            in_range, range_text
  use visco2d_card_lists, only: read_increasing_list
  use visco2d_cards, only: card_t, card_deck_t, card_error, named_real, named_integer, named_word, &
                           positional_word, check_fields_used, has_field, field_column, parse_real
  implicit none
  private

  public :: dynamic_settings_t, output_request_t, standard_gravity, theta_unconditional
  public :: integrator_wilson, integrator_newmark, integrator_hht, integrator_generalized_alpha, integrator_bathe
  public :: integrator_names
  public :: read_wilson, read_integrator, read_initial, read_drop, read_gravity, read_output, read_formulation

  !> g of DROP HEIGHT= when the deck has no GRAVITY card, and the default of GRAVITY G= (the paper's value).
  real(dp), parameter :: standard_gravity = 9.8_dp
  !> Wilson-theta is unconditionally stable for theta >= 1.37 (Bathe and Wilson 1973).
  real(dp), parameter :: theta_unconditional = 1.37_dp

  !> The time integrators of INTEGRATOR (their coefficients: visco2d_integrators).
  integer, parameter :: integrator_wilson = 1             !< Wilson-theta, the paper's (eqs. [34]-[42])
  integer, parameter :: integrator_newmark = 2            !< Newmark (BETA, GAMMA)
  integer, parameter :: integrator_hht = 3                !< Hilber-Hughes-Taylor alpha (ALPHA)
  integer, parameter :: integrator_generalized_alpha = 4  !< Chung-Hulbert generalized-alpha (RHO_INF)
  integer, parameter :: integrator_bathe = 5              !< Bathe's composite trapezoidal / 3-point backward
  character(len=17), parameter :: integrator_names(5) = [character(len=17) :: 'WILSON', 'NEWMARK', 'HHT', &
    'GENERALIZED_ALPHA', 'BATHE']

  !> Time integration and initial state of a DYNAMIC analysis.
  type :: dynamic_settings_t
    integer :: integrator = integrator_wilson  !< INTEGRATOR (default: the paper's Wilson-theta)
    real(dp) :: theta = 1.4_dp             !< Wilson theta, eqs. [34]-[37]
    real(dp) :: beta = 0.25_dp             !< Newmark beta (NEWMARK; the average-acceleration rule by default)
    real(dp) :: gamma = 0.5_dp             !< Newmark gamma (NEWMARK)
    real(dp) :: alpha = 0.05_dp            !< HHT alpha, 0 <= alpha <= 1/3 (alpha_f; often written as -alpha)
    real(dp) :: rho_infinity = 0.8_dp      !< generalized-alpha spectral radius at dt/T -> infinity, 0..1
    integer :: wilson_line = 0             !< the WILSON or INTEGRATOR card
    real(dp) :: velocity(2) = 0.0_dp       !< initial (v_r, v_z) of every free node, m/s
    logical :: acceleration_given(2) = .false.
    real(dp) :: acceleration(2) = 0.0_dp   !< initial (a_r, a_z) if given, m/s^2 (else from equilibrium)
    integer :: initial_line = 0
    real(dp) :: drop_height = -1.0_dp      !< m; < 0: no DROP card
    integer :: drop_line = 0
  end type dynamic_settings_t

  !> OUTPUT EVERY=k FIELDS=t1,t2,... ENVELOPES=YES|NO
  type :: output_request_t
    integer :: every = 1                   !< a history row every k steps (and the last step)
    logical :: envelopes = .false.         !< keep the time envelopes (visco2d_bruise) without a BRUISE card
    real(dp), allocatable :: field_times(:)  !< s, increasing: field snapshots at the first step at or after each
    integer :: line = 0
  end type output_request_t

contains

  !> WILSON THETA=1.4. Rejects theta < 1 (the method is then not consistent
  !> with its own linear-acceleration assumption); theta < 1.37 is accepted
  !> with a warning by the deck reader.
  subroutine read_wilson(cards, card, dynamics, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    type(dynamic_settings_t), intent(inout) :: dynamics
    type(error_t), allocatable, intent(inout) :: error
    call named_real(cards, card, 'THETA', dynamics%theta, error, default=1.4_dp); if (allocated(error)) return
    call check_fields_used(cards, card, error, 'WILSON THETA=1.4'); if (allocated(error)) return
    call check_theta(cards, card, dynamics%theta, error); if (allocated(error)) return
    dynamics%wilson_line = card%line
  end subroutine read_wilson

  !> INTEGRATOR WILSON [THETA=1.4] | NEWMARK [BETA=0.25] [GAMMA=0.5] |
  !> HHT [ALPHA=0.05] | GENERALIZED_ALPHA [RHO_INF=0.8] | BATHE.
  !> `warning` is set (not an error) for a conditionally stable choice.
  subroutine read_integrator(cards, card, dynamics, error, warning)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    type(dynamic_settings_t), intent(inout) :: dynamics
    type(error_t), allocatable, intent(inout) :: error
    character(:), allocatable, intent(out) :: warning
    character(:), allocatable :: name
    integer :: k
    call positional_word(cards, card, 1, 'the integrator (WILSON, NEWMARK, HHT, GENERALIZED_ALPHA or BATHE)', name, error)
    if (allocated(error)) return
    dynamics%integrator = 0
    do k = 1, size(integrator_names)
      if (name == trim(integrator_names(k))) dynamics%integrator = k
    end do
    select case (dynamics%integrator)
    case (integrator_wilson)
      call named_real(cards, card, 'THETA', dynamics%theta, error, default=1.4_dp); if (allocated(error)) return
      call check_fields_used(cards, card, error, 'INTEGRATOR WILSON THETA=1.4'); if (allocated(error)) return
      call check_theta(cards, card, dynamics%theta, error); if (allocated(error)) return
      if (dynamics%theta < theta_unconditional) warning = 'THETA = '//short_real(dynamics%theta)// &
        ' < 1.37: Wilson-theta is then only conditionally stable; a large DT may blow up (1.4 is the usual value)'
    case (integrator_newmark)
      call named_real(cards, card, 'BETA', dynamics%beta, error, default=0.25_dp); if (allocated(error)) return
      call named_real(cards, card, 'GAMMA', dynamics%gamma, error, default=0.5_dp); if (allocated(error)) return
      call check_fields_used(cards, card, error, 'INTEGRATOR NEWMARK BETA=0.25 GAMMA=0.5'); if (allocated(error)) return
      if (.not. (dynamics%gamma >= 0.5_dp .and. dynamics%gamma <= 1.0_dp)) then
        call card_error(error, cards, card, 'GAMMA must lie in 0.5 ... 1 (below 0.5 the rule amplifies every '// &
          'vibration; 0.5 adds no damping), got '//short_real(dynamics%gamma), field_column(card, 'GAMMA'))
        return
      end if
      if (.not. (dynamics%beta > 0.0_dp .and. dynamics%beta <= 0.5_dp)) then
        call card_error(error, cards, card, 'BETA must lie in 0 < BETA <= 0.5 (0.25 with GAMMA = 0.5 is the '// &
          'average-acceleration rule; the explicit BETA = 0 is not implemented), got '// &
          short_real(dynamics%beta), field_column(card, 'BETA'))
        return
      end if
      if (2.0_dp*dynamics%beta < dynamics%gamma) warning = 'BETA = '//short_real(dynamics%beta)//' < GAMMA/2: '// &
        'Newmark is then only conditionally stable (dt/T below 1/(2 pi sqrt(GAMMA/2 - BETA))); a large DT may blow up'
    case (integrator_hht)
      call named_real(cards, card, 'ALPHA', dynamics%alpha, error, default=0.05_dp); if (allocated(error)) return
      call check_fields_used(cards, card, error, 'INTEGRATOR HHT ALPHA=0.05'); if (allocated(error)) return
      if (.not. (dynamics%alpha >= 0.0_dp .and. dynamics%alpha <= 1.0_dp/3.0_dp)) then
        call card_error(error, cards, card, 'ALPHA must lie in 0 ... 1/3 (the magnitude of the HHT alpha, '// &
          'often written -1/3 ... 0), got '//short_real(dynamics%alpha), field_column(card, 'ALPHA'))
        return
      end if
    case (integrator_generalized_alpha)
      call named_real(cards, card, 'RHO_INF', dynamics%rho_infinity, error, default=0.8_dp)
      if (allocated(error)) return
      call check_fields_used(cards, card, error, 'INTEGRATOR GENERALIZED_ALPHA RHO_INF=0.8')
      if (allocated(error)) return
      if (.not. (dynamics%rho_infinity >= 0.0_dp .and. dynamics%rho_infinity <= 1.0_dp)) then
        call card_error(error, cards, card, 'RHO_INF must lie in 0 ... 1 (the spectral radius at large dt/T: '// &
          '1 keeps every vibration, 0 damps the highest at once), got '//short_real(dynamics%rho_infinity), &
          field_column(card, 'RHO_INF'))
        return
      end if
    case (integrator_bathe)
      call check_fields_used(cards, card, error, 'INTEGRATOR BATHE'); if (allocated(error)) return
    case default
      call card_error(error, cards, card, 'unknown integrator '''//name//''': expected WILSON, NEWMARK, HHT, '// &
        'GENERALIZED_ALPHA or BATHE', field_column(card, '1'))
      return
    end select
    dynamics%wilson_line = card%line
  end subroutine read_integrator

  !> Wilson's THETA: 1 <= THETA <= 10.
  subroutine check_theta(cards, card, theta, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(in) :: card
    real(dp), intent(in) :: theta
    type(error_t), allocatable, intent(inout) :: error
    if (theta < 1.0_dp) then
      call card_error(error, cards, card, 'THETA must be >= 1 (1.4 is the usual value; theta >= 1.37 is '// &
                      'unconditionally stable), got '//short_real(theta), field_column(card, 'THETA'))
    else if (theta > 10.0_dp) then
      call card_error(error, cards, card, 'THETA must be <= 10 (1.4 is the usual value), got '// &
                      short_real(theta), field_column(card, 'THETA'))
    end if
  end subroutine check_theta

  !> INITIAL VZ=.. [VR=..] [AZ=..] [AR=..]: uniform initial velocity (m/s) and,
  !> if given, acceleration (m/s^2) of every node that is not supported.
  subroutine read_initial(cards, card, dynamics, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    type(dynamic_settings_t), intent(inout) :: dynamics
    type(error_t), allocatable, intent(inout) :: error
    call named_real(cards, card, 'VR', dynamics%velocity(1), error, default=0.0_dp, range=speed_range)
    if (allocated(error)) return
    call named_real(cards, card, 'VZ', dynamics%velocity(2), error, default=0.0_dp, range=speed_range)
    if (allocated(error)) return
    dynamics%acceleration_given = [has_field(card, 'AR'), has_field(card, 'AZ')]
    call named_real(cards, card, 'AR', dynamics%acceleration(1), error, default=0.0_dp, range=acceleration_range)
    if (allocated(error)) return
    call named_real(cards, card, 'AZ', dynamics%acceleration(2), error, default=0.0_dp, range=acceleration_range)
    if (allocated(error)) return
    call check_fields_used(cards, card, error, 'INITIAL VZ=.. [VR=..] [AZ=..] [AR=..]'); if (allocated(error)) return
    if (.not. any([has_field(card, 'VR'), has_field(card, 'VZ'), dynamics%acceleration_given])) then
      call card_error(error, cards, card, 'INITIAL needs at least one of VZ=, VR=, AZ=, AR='); return
    end if
    dynamics%initial_line = card%line
  end subroutine read_initial

  !> DROP HEIGHT=h: the body starts at contact with VZ = -sqrt(2 g h).
  subroutine read_drop(cards, card, dynamics, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    type(dynamic_settings_t), intent(inout) :: dynamics
    type(error_t), allocatable, intent(inout) :: error
    call named_real(cards, card, 'HEIGHT', dynamics%drop_height, error, range=drop_height_range)
    if (allocated(error)) return
    call check_fields_used(cards, card, error, 'DROP HEIGHT=..'); if (allocated(error)) return
    dynamics%drop_line = card%line
  end subroutine read_drop

  !> GRAVITY [G=9.8]: body force rho g in -z, m/s^2.
  subroutine read_gravity(cards, card, gravity, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    real(dp), intent(out) :: gravity
    type(error_t), allocatable, intent(inout) :: error
    call named_real(cards, card, 'G', gravity, error, default=standard_gravity, range=gravity_range)
    if (allocated(error)) return
    call check_fields_used(cards, card, error, 'GRAVITY [G=9.8]'); if (allocated(error)) return
  end subroutine read_gravity

  !> OUTPUT EVERY=k [FIELDS=t1,t2,...] [ENVELOPES=YES|NO]: history every k
  !> steps, fields at those times (s), and the time envelopes of the failure
  !> measures (visco2d_bruise) kept even without a BRUISE card.
  subroutine read_output(cards, card, output, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    type(output_request_t), intent(inout) :: output
    type(error_t), allocatable, intent(inout) :: error
    character(:), allocatable :: list, envelopes
    character(len=*), parameter :: form = 'OUTPUT EVERY=k [FIELDS=t1,t2,...] [ENVELOPES=YES|NO]'
    call named_integer(cards, card, 'EVERY', output%every, error, default=1); if (allocated(error)) return
    call named_word(cards, card, 'FIELDS', list, error, default=''); if (allocated(error)) return
    call named_word(cards, card, 'ENVELOPES', envelopes, error, default='NO'); if (allocated(error)) return
    call check_fields_used(cards, card, error, form); if (allocated(error)) return
    select case (envelopes)
    case ('YES'); output%envelopes = .true.
    case ('NO'); output%envelopes = .false.
    case default
      call card_error(error, cards, card, 'ENVELOPES must be YES or NO, got "'//envelopes//'"', &
                      field_column(card, 'ENVELOPES')); return
    end select
    if (output%every < 1) then
      call card_error(error, cards, card, 'EVERY must be >= 1, got '//integer_text(output%every), field_column(card,&
        'EVERY')); return
    end if
    if (allocated(output%field_times)) deallocate(output%field_times)
    call read_increasing_list(cards, card, 'FIELDS', list, 'times >= 0 s', 'times', time_range, output%field_times, &
                              error)
    if (allocated(error)) return
    output%line = card%line
  end subroutine read_output

  !> FORMULATION STANDARD | BBAR: the element's strain-displacement matrix,
  !> full 2x2 integration (the legacy element) or B-bar (mean dilatation).
  subroutine read_formulation(cards, card, formulation, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    integer, intent(out) :: formulation
    type(error_t), allocatable, intent(inout) :: error
    character(:), allocatable :: word
    call positional_word(cards, card, 1, 'element formulation (STANDARD or BBAR)', word, error)
    if (allocated(error)) return
    call check_fields_used(cards, card, error, 'FORMULATION STANDARD | BBAR'); if (allocated(error)) return
    select case (word)
    case ('STANDARD')
      formulation = formulation_standard
    case ('BBAR')
      formulation = formulation_bbar
    case default
      call card_error(error, cards, card, 'formulation must be STANDARD or BBAR, got "'//word//'"', &
                      field_column(card, '1'))
    end select
  end subroutine read_formulation
end module visco2d_dynamic_cards
