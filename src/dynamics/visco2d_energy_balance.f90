!> The energy books of a dynamic run and the instability check: measurement
!> beside the step, not part of it. Every sub-step books the trapezoidal
!> work of every force over its increment du (exact for forces linear in u,
!> as the elastic internal force is) and the kinetic energy; the run stops
!> with an error if kinetic + internal energy grows far beyond what can
!> have been put into the body, or keeps growing past it step after step.
module visco2d_energy_balance
  use visco2d_kinds, only: dp
  use visco2d_strings, only: integer_text, table_real, message_real
  use visco2d_deck, only: deck_t
  use visco2d_assembly, only: node_dof
  use visco2d_contact, only: contact_t, contact_partner_sum
  use visco2d_pad_projection, only: pair_compliance
  implicit none
  private

  public :: energy_balance_t, energy_growth_limit, balance_start, balance_substep, balance_contact_loss, balance_growth

  !> The run stops as unstable when kinetic + internal energy exceeds this
  !> multiple of the energy that can have been put into the body: the initial
  !> kinetic energy plus the positive work of loads, gravity and prescribed
  !> (FIX) motions, step by step. The plate's reactions are not counted: a
  !> rigid fixed plate does no positive work on the body, so a diverging
  !> solution cannot raise the bound through them. The multiple is widened by
  !> the integrator's transient overshoot (energy_overshoot of visco2d_integrators).
  real(dp), parameter :: energy_growth_limit = 100.0_dp

  !> The growth-rate test: the run also stops when the energy in excess of that
  !> input has grown by at least `growth_rate_limit` in each of the last
  !> `growth_window` steps and has passed `growth_floor` times the input (a
  !> stable step cannot keep raising it: its spectral radius is below 1, and
  !> a first-step overshoot decays after one or two steps). The floor: a
  !> stable but conditionally stable rule near its limit (NEWMARK BETA=1/6,
  !> WILSON THETA=1) keeps an invariant that is not the physical energy, so
  !> the physical energy of one mode swings up to 1/(1 - (Omega/Omega_c)^2)
  !> times its start, and can climb by 1.5 three steps in a row: 5.3 at 0.9
  !> of the limit Omega_c, 10.3 at 0.95. A floor of 10 lets those stable runs
  !> go on; a run that really diverges passes it a few steps later.
  integer, parameter :: growth_window = 3
  real(dp), parameter :: growth_rate_limit = 1.5_dp
  real(dp), parameter :: growth_floor = 10.0_dp

  !> The energy books (per radian in axisymmetry, per metre in plane strain).
  type :: energy_balance_t
    real(dp) :: kinetic = 0.0_dp, kinetic0 = 0.0_dp, internal_work = 0.0_dp, load_work = 0.0_dp
    real(dp) :: support_work = 0.0_dp, gravity_work = 0.0_dp, contact_loss = 0.0_dp
    real(dp) :: positive_input = 0.0_dp   !< initial kinetic energy + positive work of loads, gravity, FIX motions
    real(dp) :: excess(0:growth_window) = 0.0_dp   !< kinetic + internal energy - positive_input, the last steps
    integer :: growth_steps = 0           !< consecutive steps of excess growth by >= growth_rate_limit
    real(dp) :: balance = 0.0_dp, balance_max = 0.0_dp, input_max = 0.0_dp
    real(dp) :: growth_limit = energy_growth_limit   !< energy_growth_limit times the overshoot factor
  end type energy_balance_t

contains

  !> The books at t = 0: only the initial kinetic energy.
  subroutine balance_start(book, mass, v)
    type(energy_balance_t), intent(out) :: book
    real(dp), intent(in) :: mass(:), v(:)
    book%kinetic0 = 0.5_dp*dot_product(mass, v**2)
    book%kinetic = book%kinetic0
    book%positive_input = book%kinetic0
    book%input_max = book%kinetic0
  end subroutine balance_start

  !> Book a sub-step of increment du ending with velocity v_next: the
  !> trapezoidal work of the internal force, the loads, the FIX supports
  !> (an input) and gravity, and the balance. The fixed rigid plate does no
  !> work: the kinetic energy of a node it stops is booked as contact_loss,
  !> and the trapezoidal reaction work of the step a node touches (its large
  !> reaction times its free travel to the plate) would be an artifact (26 %
  !> of the input at nu = 0.4999). Returns kinetic + internal energy.
  subroutine balance_substep(book, mass, gravity, supports, du, v_next, load, load_next, internal, internal_next, &
                          reaction, reaction_next, energy)
    type(energy_balance_t), intent(inout) :: book
    real(dp), intent(in) :: mass(:), gravity(:), du(:), v_next(:)
    logical, intent(in) :: supports(:)
    real(dp), intent(in) :: load(:), load_next(:), internal(:), internal_next(:), reaction(:), reaction_next(:)
    real(dp), intent(out) :: energy
    book%internal_work = book%internal_work + 0.5_dp*dot_product(internal + internal_next, du)
    associate (load_increment => 0.5_dp*dot_product(load + load_next, du), &
               support_increment => 0.5_dp*sum(merge(reaction + reaction_next, 0.0_dp, supports)*du), &
               gravity_increment => dot_product(gravity, du))
    book%load_work = book%load_work + load_increment
    book%support_work = book%support_work + support_increment
    book%gravity_work = book%gravity_work + gravity_increment
    book%positive_input = book%positive_input + max(0.0_dp, load_increment) + max(0.0_dp, support_increment) + &
                          max(0.0_dp, gravity_increment)
    end associate
    book%kinetic = 0.5_dp*dot_product(mass, v_next**2)
    book%balance = book%kinetic + book%internal_work + book%contact_loss - &
                   (book%kinetic0 + book%load_work + book%support_work + book%gravity_work)
    book%input_max = max(book%input_max, book%kinetic0 + abs(book%load_work + book%support_work + book%gravity_work))
    book%balance_max = max(book%balance_max, abs(book%balance))
    energy = book%kinetic + book%internal_work
  end subroutine balance_substep

  !> The kinetic energy (velocity v before the sub-step's update) of the
  !> components the plate stopped in this sub-step. On a pad, the energy of
  !> the inelastic collision of the node with the surface under it
  !> (visco2d_pad_projection): 1/2 mu (v - v_surface)^2 with the reduced mass
  !> 1/mu = 1/m + sum_k w_k^2/m_k of the node and the surface nodes (the
  !> coupling of pairs touching in the same sub-step through a shared
  !> surface node is left out); on the rigid plate mu = m.
  subroutine balance_contact_loss(book, deck, contact, mass, v)
    type(energy_balance_t), intent(inout) :: book
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    real(dp), intent(in) :: mass(:), v(:)
    integer :: i, node
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (.not. contact%touched(node)) cycle
      associate (r => node_dof(deck%mesh, node, 1), z => node_dof(deck%mesh, node, 2))
      book%contact_loss = book%contact_loss + 0.5_dp/pair_compliance(contact%partner, contact%weight, mass, z)* &
                          (v(z) - contact_partner_sum(deck, contact, v, node, 2))**2
      if (contact%stick) book%contact_loss = book%contact_loss + &
        0.5_dp/pair_compliance(contact%partner, contact%weight, mass, r)* &
        (v(r) - contact_partner_sum(deck, contact, v, node, 1))**2
      end associate
    end do
  end subroutine balance_contact_loss

  !> The instability test after a step (kinetic + internal energy `energy`):
  !> the bound growth_limit times the positive input, and the growth rate of
  !> the excess over it. `what` is allocated (the reason) when it fails.
  subroutine balance_growth(book, energy, what)
    type(energy_balance_t), intent(inout) :: book
    real(dp), intent(in) :: energy
    character(:), allocatable, intent(out) :: what
    book%excess(0:growth_window - 1) = book%excess(1:growth_window)
    book%excess(growth_window) = energy - book%positive_input
    if (book%excess(growth_window) >= growth_rate_limit*book%excess(growth_window - 1) .and. &
        book%excess(growth_window - 1) > 0.0_dp) then
      book%growth_steps = book%growth_steps + 1
    else
      book%growth_steps = 0
    end if
    if (energy > book%growth_limit*book%positive_input .and. energy > 0.0_dp) then
      what = 'the kinetic + internal energy ('//table_real(energy)//' J) has grown past '// &
        message_real(book%growth_limit)//' times the energy put into the body ('//table_real(book%positive_input)// &
        ' J: the initial kinetic energy and the positive work of loads, gravity and prescribed motions)'
    else if (book%growth_steps >= growth_window .and. &
             book%excess(growth_window) > growth_floor*book%positive_input) then
      what = 'the kinetic + internal energy ('//table_real(energy)//' J) exceeds '//message_real(growth_floor)// &
        ' times the energy put into the body ('//table_real(book%positive_input)//' J) and has grown by '// &
        message_real(growth_rate_limit)//' or more in each '// &
        'of the last '//integer_text(growth_window)//' steps (by '// &
        message_real(book%excess(growth_window)/max(book%excess(0), tiny(1.0_dp)))//' in all)'
    end if
  end subroutine balance_growth
end module visco2d_energy_balance
