!> STATIC with a PLATE: the body pressed onto the rigid plate, solved by
!> following the load path exactly (the contact set changes at the load
!> factors where a free node reaches the plate or a contact node's reaction
!> reaches zero), on the rigid plate or on a PAD. Uses the contact state of
!> visco2d_contact; the solves of each contact set are visco2d_constrained_system's.
module visco2d_static_contact
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: integer_text, table_real
  use visco2d_deck, only: deck_t
  use visco2d_assembly, only: node_dof, band_vector, support_mask, external_load, gravity_load, lumped_mass
  use visco2d_static, only: static_solution_t, solve_static, static_record
  use visco2d_plastic_static, only: plastic_plate_t, plastic_summary_t, solve_plastic_static, plastic_record
  use visco2d_stress_recovery, only: node_stress
  use visco2d_record, only: record_t, record_put_real, record_put_integer
  use visco2d_bruise, only: bruise_static
  use visco2d_pad_mesh, only: is_pad_node, body_nodes, body_elements
  use visco2d_advice, only: deformation_warnings, largest_strain
  use visco2d_constrained_system, only: constrained_system_t, constrained_system_create, constrained_system_solve
  use visco2d_contact, only: contact_t, contact_create, contact_count, contact_force, contact_gap, &
                             contact_pressure, contact_radius, contact_partner_sum, pad_compression
  implicit none
  private

  public :: solve_static_contact, solve_plastic_static_contact

  !> States of a node on the static contact path.
  integer, parameter :: node_free = 0      !< off the plate
  integer, parameter :: node_stuck = 1     !< on the plate, u_r and u_z held (STICK)
  integer, parameter :: node_sliding = 2   !< on the plate, u_z held (SLIP; a STICK node freed at zero force)
  !> Block changes at one load factor that may fail to lower the count of
  !> violating nodes before they change one at a time (Judice and Pires).
  integer, parameter :: strikes_allowed = 10
  !> The error of a static contact solution that overflowed.
  character(*), parameter :: not_finite_message = 'the static contact solution is not a finite number (it '// &
    'overflowed): the moduli, loads or sizes of the deck are out of any physical range; no results were written'
  !> Two load factors closer than this are the same point of the static path.
  real(dp), parameter :: same_factor = 1.0e-12_dp

  !> The static contact path: its state at load factor lambda and the
  !> response u = base + lambda rate of the current contact set.
  type :: static_path_t
    real(dp) :: load_factor = 0.0_dp             !< lambda, 0 .. 1
    integer, allocatable :: state(:)             !< (nnode) node_free, node_stuck, node_sliding
    integer, allocatable :: changes(:)           !< (nnode) changes of state at this load factor
    logical, allocatable :: freed_here(:)        !< (nnode) freed from sticking at this load factor
    real(dp), allocatable :: values(:)           !< (2 nnode) held displacements (band order)
    real(dp), allocatable :: base(:), rate(:)    !< u_0 and u_1 of the current set
    real(dp), allocatable :: reaction_base(:), reaction_rate(:)
    integer :: solves = 0                        !< factorizations along the path
    integer :: best_violations = huge(1)         !< fewest nodes past their limit at this load factor
    integer :: strikes = 0                       !< block changes since that count last fell
  end type static_path_t

contains

  !> STATIC with a PLATE: the body pressed onto the plate (loads, gravity,
  !> prescribed support displacements), followed as the load grows from 0 to
  !> its full value (load factor lambda). While the contact set stands the
  !> response is linear in lambda, u = u_0 + lambda u_1, so the path is
  !> followed exactly: the set changes at the smallest lambda at which a free
  !> node reaches the plate or a contact node's z reaction reaches zero.
  !>
  !> A node that reaches the plate is put on it where it is: u_z = Z - z and,
  !> with STICK, u_r = its u_r at that moment (it keeps the tangential
  !> position it touched at, as in the dynamic STICK: the incremental no-slip
  !> contact of Mossakovskii and Spence). A contact node is freed only when
  !> its reaction turns tensile (whatever RELEASE says: a static contact set
  !> must push everywhere). A stuck node freed at some lambda that goes
  !> through the plate at the same lambda slides from then on (u_z held, u_r
  !> free): at zero normal force it can carry no tangential force, and with
  !> u_z alone held the reaction and the approach of a node have opposite
  !> signs, so it cannot alternate between pulling and going through.
  !>
  !> With SLIP this is the path of frictionless contact, whose end is the one
  !> set in which every contact node pushes and no free node is through the
  !> plate. (Holding a STICK node at u_r = 0, where it was before the load,
  !> is what a one-shot iteration does; the edge nodes then pull when held
  !> and go through the plate when freed, and the set never settles.)
  subroutine solve_static_contact(deck, record, error)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    type(error_t), allocatable, intent(out) :: error
    type(contact_t) :: contact
    type(static_solution_t) :: solution
    type(static_path_t) :: path
    logical, allocatable :: held(:)

    associate (mesh => deck%mesh)
    call contact_create(deck, contact)
    call follow_static_path(deck, contact, path, error)
    if (allocated(error)) return
    ! The final state, solved again from the final set for its stresses.
    held = static_held(deck, contact, path%state)
    if (contact%pad) then                               ! the path's own constrained solution at full load
      call solve_static(deck%mesh, deck%materials, deck%settings, deck%loads, deck%source, solution, error, &
        given=path%base + path%rate)
    else
      call solve_static(deck%mesh, deck%materials, deck%settings, deck%loads, deck%source, solution, error, held, &
        path%values)
    end if
    if (allocated(error)) return
    call record_contact_state(deck, contact, solution, path%solves + 1, record, error, &
                              sliding=count(path%state == node_sliding))
    end associate
  end subroutine solve_static_contact

  !> STATIC with a PLATE and a PLASTIC material: the load-incremented Newton
  !> solve of visco2d_plastic_static with the frictionless plate as an
  !> active set in every increment (PLATE SLIP on the rigid plate; the deck
  !> reader refuses STICK and a PAD with plasticity), then the checks and
  !> keys of the elastic static contact (record_contact_state) and the
  !> plastic keys.
  subroutine solve_plastic_static_contact(deck, record, error)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    type(error_t), allocatable, intent(out) :: error
    type(contact_t) :: contact
    type(plastic_plate_t) :: plate
    type(static_solution_t) :: solution
    type(plastic_summary_t) :: summary
    integer :: i, node
    call contact_create(deck, contact)
    plate%z = contact%z_plate
    plate%tolerance = contact%tolerance
    plate%candidates = contact%candidates
    plate%active = contact%active
    do i = 1, size(contact%candidates)                 ! on the plate at the start, as on the elastic path
      node = contact%candidates(i)
      if (deck%mesh%xy(2, node) - contact%z_plate <= contact%tolerance) plate%active(node) = .true.
    end do
    call solve_plastic_static(deck%mesh, deck%materials, deck%settings, deck%loads, deck%source, solution, summary, &
                              error, plate)
    if (allocated(error)) return
    contact%active = plate%active
    contact%iterations = summary%contact_changes
    call record_contact_state(deck, contact, solution, summary%iterations, record, error)
    if (allocated(error)) return
    call plastic_record(deck%settings, summary, record)
  end subroutine solve_plastic_static_contact

  !> The final static state on the plate (or the pad) checked (finite,
  !> settled, the pad not pressed through, in equilibrium) and recorded: the
  !> static keys and fields, the deformation warnings, the bruise, and the
  !> contact keys (force, approach, pole pressure, contact radius).
  subroutine record_contact_state(deck, contact, solution, factorizations, record, error, sliding)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    type(static_solution_t), intent(in) :: solution
    integer, intent(in) :: factorizations            !< matrix factorizations of the solve
    type(record_t), intent(inout) :: record
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in), optional :: sliding         !< STICK nodes that slide at the end (the elastic path's)
    real(dp), allocatable :: u(:), reaction(:), pressure(:), weight(:)
    real(dp) :: q, surface(4)
    integer :: node
    associate (mesh => deck%mesh)
    u = band_vector(mesh, solution%displacement)
    reaction = band_vector(mesh, solution%reaction)
    if (.not. (all(ieee_is_finite(u)) .and. all(ieee_is_finite(reaction)) .and. all(ieee_is_finite(solution%stress)))) then
      call set_error(error, not_finite_message, file=deck%cards%file)
      return
    end if
    call check_settled(deck, contact, u, reaction, error)
    if (allocated(error)) return
    if (contact%pad) then                               ! the pad's top would be under the rigid plate
      if (pad_compression(deck, contact, u) >= deck%pad%thickness) then
        call set_error(error, 'the pad is compressed '//table_real(1.0e3_dp*pad_compression(deck, contact, u))// &
          ' mm, more than its thickness of '//table_real(1.0e3_dp*deck%pad%thickness)//' mm (its own weight and '// &
          'the body''s press it through the rigid plate): far beyond the small-strain pad model; make the '// &
          'PAD stiffer or thinner', file=deck%cards%file, line=deck%pad%line, card='PAD')
        return
      end if
    end if
    call check_equilibrium(deck, contact, u, reaction, error)
    if (allocated(error)) return
    call static_record(deck%mesh, deck%settings, deck%probes, solution, record, body_nodes(deck), body_elements(deck))
    associate (body => body_elements(deck))            ! beyond the small-strain model: warned, as in DYNAMIC
    call deformation_warnings(deck, record, largest_strain(solution%strain(:, :, :body)), &
                              largest_strain(solution%strain(:, :, body + 1:)))
    end associate
    call bruise_static(deck, solution%stress, solution%strain, record)
    allocate(pressure(mesh%nnode))
    call contact_pressure(deck, contact, reaction, pressure, q)
    weight = lumped_mass(deck%mesh, deck%settings, deck%materials, volume=.true.)
    call record_put_integer(record, 'factorizations', factorizations)
    call record_put_integer(record, 'contact_iterations', contact%iterations)
    call record_put_integer(record, 'contact_nodes', contact_count(contact))
    if (contact%stick .and. present(sliding)) call record_put_integer(record, 'contact_sliding_nodes', sliding)
    call record_put_real(record, 'force_N', contact_force(deck, contact, reaction))
    if (contact%pad) then                               ! the body's mean u_z, less the pad's compression
      do node = 1, mesh%nnode
        if (is_pad_node(deck, node)) weight(node_dof(mesh, node, 1):node_dof(mesh, node, 2)) = 0.0_dp
      end do
    end if
    call record_put_real(record, 'alpha_mm', -1.0e3_dp*(dot_product(weight(2::2), u(2::2))/sum(weight(2::2)) &
                                                        + pad_compression(deck, contact, u)))
    if (contact%pad) call record_put_real(record, 'pad_compression_mm', 1.0e3_dp*pad_compression(deck, contact, u))
    call record_put_real(record, 'q_MPa', 1.0e-6_dp*q)
    surface = node_stress(mesh, solution%stress, contact%pole)
    call record_put_real(record, 'q_surface_MPa', -1.0e-6_dp*surface(2))
    call record_put_real(record, 'contact_radius_mm', 1.0e3_dp*contact_radius(deck, contact))
    end associate
  end subroutine record_contact_state

  !> The static contact path (solve_static_contact) from lambda = 0 to 1:
  !> the final contact set in contact%active and path%state, the held values in path%values.
  subroutine follow_static_path(deck, contact, path, error)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(inout) :: contact
    type(static_path_t), intent(out) :: path
    type(error_t), allocatable, intent(out) :: error
    type(constrained_system_t) :: system
    logical, allocatable :: held(:)
    real(dp), allocatable :: change_at(:)
    real(dp) :: next
    integer :: i, node, limit, event

    associate (mesh => deck%mesh)
    allocate(path%state(mesh%nnode), path%changes(mesh%nnode), path%freed_here(mesh%nnode), &
             path%values(2*mesh%nnode), path%base(2*mesh%nnode), path%rate(2*mesh%nnode))
    path%state = node_free
    path%values = 0.0_dp
    path%base = 0.0_dp
    path%rate = 0.0_dp
    path%changes = 0
    path%freed_here = .false.
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (mesh%xy(2, node) - contact%z_plate <= contact%tolerance) call path_touch(deck, contact, path, node)
    end do
    call constrained_system_create(deck, contact, system, error)
    if (allocated(error)) return
    limit = 50 + 10*size(contact%candidates)
    do event = 1, limit
      held = static_held(deck, contact, path%state)
      call constrained_system_solve(deck, system, held, path%values, path%base, path%rate, path%reaction_base, &
                             path%reaction_rate, error)
      path%solves = path%solves + 1
      if (allocated(error)) then
        error%message = error%message//' (with '//integer_text(count(contact%active))//' node(s) on the plate at '// &
          table_real(100.0_dp*path%load_factor)//' % of the load: a body that only rests on the plate needs a load '// &
          'that presses it on, and supports that stop it from turning or sliding)'
        if (error%line == 0) then                       ! located at the PLATE card, which holds the body
          error%line = deck%plate%line
          error%card = 'PLATE'
        end if
        return
      end if
      if (.not. (all(ieee_is_finite(path%base)) .and. all(ieee_is_finite(path%rate)) .and. &
                 all(ieee_is_finite(path%reaction_base)) .and. all(ieee_is_finite(path%reaction_rate)))) then
        call set_error(error, not_finite_message, file=deck%cards%file)
        return
      end if
      change_at = change_factors(deck, contact, path)
      next = minval(change_at)
      if (next > 1.0_dp) return                         ! the set stands to the full load
      if (next > path%load_factor + same_factor) then   ! moving on along the path
        path%load_factor = next
        path%changes = 0
        path%freed_here = .false.
        path%best_violations = huge(1)
        path%strikes = 0
        call apply_changes(deck, contact, path, change_at <= next + same_factor)
      else                                              ! again at the same load factor
        call apply_changes(deck, contact, path, immediate_changes(deck, contact, path, change_at))
      end if
      contact%iterations = contact%iterations + 1
    end do
    node = maxloc(path%changes, dim=1)
    call set_error(error, 'the contact set did not settle after '//integer_text(limit)//' changes: at '// &
      table_real(100.0_dp*path%load_factor)//' % of the load, node '//integer_text(mesh%node_id(node))//' (r = '// &
      table_real(1.0e3_dp*mesh%xy(1, node))//' mm) went '//integer_text(path%changes(node))//' times between free and held '// &
      '(it pulls on the plate when held and goes through it when free)'//slip_hint(contact), &
      file=deck%cards%file, line=deck%plate%line, card='PLATE')
    end associate
  end subroutine follow_static_path

  !> The advice that ends a STICK contact error.
  pure function slip_hint(contact) result(text)
    type(contact_t), intent(in) :: contact
    character(:), allocatable :: text
    text = ''
    if (contact%stick) text = ' (frictionless contact, PLATE ... SLIP, always settles)'
  end function slip_hint

  !> Per node, the load factor in [lambda, 1] at which the current set stops
  !> holding for it (huge if it holds to the full load): a free node reaches
  !> the plate (its gap at lambda = 1 is below -tolerance), a contact node's
  !> z reaction reaches zero (it is tensile at lambda = 1). Both are linear
  !> in the load factor; lambda itself if the node is already past it.
  function change_factors(deck, contact, path) result(factor)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    type(static_path_t), intent(in) :: path
    real(dp) :: factor(deck%mesh%nnode)
    real(dp) :: now, last, small
    integer :: i, node, z
    factor = huge(1.0_dp)
    small = reaction_tolerance(deck, contact, path)
    associate (lambda => path%load_factor)
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      z = node_dof(deck%mesh, node, 2)
      if (path%state(node) == node_free) then
        now = contact_gap(deck, contact, path%base + lambda*path%rate, node)
        last = contact_gap(deck, contact, path%base + path%rate, node)
        if (last >= -contact%tolerance) cycle
        factor(node) = lambda
        if (now > contact%tolerance) factor(node) = lambda + (1.0_dp - lambda)*now/(now - last)
      else
        now = path%reaction_base(z) + lambda*path%reaction_rate(z)
        last = path%reaction_base(z) + path%reaction_rate(z)
        if (last >= -small) cycle
        factor(node) = lambda
        if (now > small) factor(node) = lambda + (1.0_dp - lambda)*now/(now - last)
      end if
    end do
    end associate
  end function change_factors

  !> Round-off level of the z reactions of the path (N per radian): 1e-9 of the largest.
  real(dp) function reaction_tolerance(deck, contact, path) result(small)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    type(static_path_t), intent(in) :: path
    integer :: i, z
    small = 0.0_dp
    do i = 1, size(contact%candidates)
      if (.not. contact%active(contact%candidates(i))) cycle
      z = node_dof(deck%mesh, contact%candidates(i), 2)
      small = max(small, abs(path%reaction_base(z) + path%reaction_rate(z)), &
                  abs(path%reaction_base(z) + path%load_factor*path%reaction_rate(z)))
    end do
    small = 1.0e-9_dp*small
  end function reaction_tolerance

  !> The changes to make at the same load factor again (the state is past a
  !> limit there: at a degenerate point where several nodes have zero gap
  !> and zero force, such as a flat face resting on the plate at lambda = 0,
  !> or after a freed stuck node's tangential reaction is gone). The block
  !> principal pivoting of Judice and Pires: every node past its limit
  !> changes at once while that lowers the count of such nodes below its
  !> best at this load factor, or has not failed to for `strikes_allowed`
  !> changes; otherwise only the first such node in candidate order changes
  !> (Murty's least-index rule), until the count is below its best again.
  !> That ends for the frictionless problem, whose held z equations have a
  !> positive definite Schur complement (a P-matrix complementarity
  !> problem); block pivoting alone can cycle, the least-index rule alone is
  !> slow (over 300 changes for a strip of 39 bottom nodes lifted at one end,
  !> where the one-shot iteration needed 28; with 10 strikes at most 48 over
  !> 200 random lifted strips and discs).
  function immediate_changes(deck, contact, path, change_at) result(due)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    type(static_path_t), intent(inout) :: path
    real(dp), intent(in) :: change_at(:)
    logical :: due(deck%mesh%nnode)
    integer :: i, node, violations
    due = change_at <= path%load_factor + same_factor
    violations = count(due)
    if (violations < path%best_violations) then
      path%best_violations = violations
      path%strikes = 0
      return
    end if
    path%strikes = path%strikes + 1
    if (path%strikes <= strikes_allowed) return
    due = .false.
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (change_at(node) > path%load_factor + same_factor) cycle
      due(node) = .true.
      return
    end do
  end function immediate_changes

  !> Change the state of the `due` nodes at path%load_factor: a free node is
  !> put on the plate, a contact node is freed.
  subroutine apply_changes(deck, contact, path, due)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(inout) :: contact
    type(static_path_t), intent(inout) :: path
    logical, intent(in) :: due(:)
    integer :: i, node
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (.not. due(node)) cycle
      path%changes(node) = path%changes(node) + 1
      if (path%state(node) == node_free) then
        call path_touch(deck, contact, path, node)
      else
        path%freed_here(node) = path%freed_here(node) .or. path%state(node) == node_stuck
        path%state(node) = node_free
        contact%active(node) = .false.
      end if
    end do
  end subroutine apply_changes

  !> Put a node on the plate where the path has it: u_z = Z - z; with STICK
  !> also u_r held at its present value, unless the node was freed from
  !> sticking at this load factor (then it slides). On a pad the same values
  !> hold relative to the surface under the node (the gap is 0).
  subroutine path_touch(deck, contact, path, node)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(inout) :: contact
    type(static_path_t), intent(inout) :: path
    integer, intent(in) :: node
    integer :: r
    contact%active(node) = .true.
    path%values(node_dof(deck%mesh, node, 2)) = contact%z_plate - deck%mesh%xy(2, node)
    path%state(node) = node_sliding
    if (.not. contact%stick .or. path%freed_here(node)) return
    path%state(node) = node_stuck
    r = node_dof(deck%mesh, node, 1)
    path%values(r) = path%base(r) + path%load_factor*path%rate(r) &
                     - contact_partner_sum(deck, contact, path%base + path%load_factor*path%rate, node, 1)
  end subroutine path_touch

  !> The equations held by the plate on the static path: u_z of every contact
  !> node, u_r of the stuck ones.
  function static_held(deck, contact, state) result(held)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    integer, intent(in) :: state(:)
    logical :: held(2*deck%mesh%nnode)
    integer :: i, node
    held = .false.
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (state(node) == node_free) cycle
      held(node_dof(deck%mesh, node, 2)) = .true.
      if (state(node) == node_stuck) held(node_dof(deck%mesh, node, 1)) = .true.
    end do
  end function static_held

  !> The body's nodes off the plate and off its supports carry no force: their
  !> residual K u - R (the `reaction`) must be below `round_off_balance` of
  !> the forces the body carries: the largest load (loads and gravity),
  !> support reaction or contact reaction. (Against the contact reactions
  !> alone, below 1e-9 of them, a body the plate never touches, held by its
  !> supports, was refused for a residual of 6e-13 N against reactions of 0.)
  !> A solve of a singular system that passed the factor's pivot test fails
  !> here instead of giving a body out of equilibrium: its residual is of the
  !> order of the loads themselves (9 to 12 times them for the free sphere,
  !> every solver). A sound system leaves the round-off of its solution: on a
  !> PAD the body rides down with the pad's compression, and that rigid
  !> motion formed through the body's stiffness leaves about 1e-16 times
  !> (compression / the body's own deformation) of the loads, which is also
  !> the relative round-off of the body's stresses (a steel sphere, E = 2e11,
  !> on a foam pad of E = 1e5: 1.1e-7; the band, profile and CHOLMOD
  !> solutions agree to 2e-8). Between `round_off_balance` and
  !> `singular_balance` the error says it is round-off, not a singular
  !> stiffness.
  subroutine check_equilibrium(deck, contact, u, reaction, error)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    real(dp), intent(in) :: u(:), reaction(:)
    type(error_t), allocatable, intent(out) :: error
    !> A residual above this fraction of the loads is a body out of balance
    !> (a singular stiffness), below it round-off.
    real(dp), parameter :: singular_balance = 1.0e-3_dp
    !> The round-off a static contact solution may leave, of the loads: its
    !> stresses keep 6 digits.
    real(dp), parameter :: round_off_balance = 1.0e-6_dp
    logical, allocatable :: supported(:)
    character(:), allocatable :: where, round_off
    real(dp) :: largest, residual, scale, compression, deformation
    integer :: i, node, equation, worst
    largest = 0.0_dp
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (contact%active(node)) largest = max(largest, maxval(abs(reaction(node_dof(deck%mesh, node, 1): &
                                                                          node_dof(deck%mesh, node, 2)))))
    end do
    supported = support_mask(deck%mesh, deck%settings, deck%loads)
    scale = max(largest, maxval(abs(external_load(deck%mesh, deck%settings, deck%loads, 0.0_dp) + &
                                    gravity_load(deck%mesh, deck%settings, deck%materials, deck%loads))), &
                maxval(abs(merge(reaction, 0.0_dp, supported))), tiny(1.0_dp))
    residual = 0.0_dp
    worst = 0
    do node = 1, body_nodes(deck)
      if (contact%active(node)) cycle
      do equation = node_dof(deck%mesh, node, 1), node_dof(deck%mesh, node, 2)
        if (supported(equation)) cycle
        if (abs(reaction(equation)) > residual) then
          residual = abs(reaction(equation))
          worst = node
        end if
      end do
    end do
    if (worst == 0 .or. residual <= round_off_balance*scale) return
    where = 'the static solution is not in equilibrium at node '//integer_text(deck%mesh%node_id(worst))//' (r = '// &
      table_real(1.0e3_dp*deck%mesh%xy(1, worst))//' mm): a nodal force of '//table_real(residual)//' where none acts, '// &
      'against loads and reactions up to '//table_real(scale)
    if (residual >= singular_balance*scale) then
      call set_error(error, where//'; the stiffness may be singular (a body free to move): fix its rigid motions', &
                     file=deck%cards%file, line=deck%plate%line, card='PLATE')
      return
    end if
    round_off = ' ('//table_real(residual/scale)//' of them; '//table_real(round_off_balance)//' allowed): the round-off '// &
      'of an ill-conditioned system, not a singular stiffness'
    if (contact%pad) then
      compression = pad_compression(deck, contact, u)
      deformation = 0.0_dp
      do node = 1, body_nodes(deck)
        deformation = max(deformation, abs(u(node_dof(deck%mesh, node, 2)) + compression))
      end do
      call set_error(error, where//round_off//': the body rides down '//table_real(1.0e3_dp*compression)// &
        ' mm with the pad''s compression, '//table_real(compression/max(deformation, tiny(1.0_dp)))// &
        ' times its own deformation, and that motion formed through its stiffness leaves the residual; make '// &
        'the PAD thinner or stiffer (closer to the body''s modulus)', &
        file=deck%cards%file, line=deck%pad%line, card='PAD')
    else
      call set_error(error, where//round_off//' (moduli or sizes far apart)', &
        file=deck%cards%file, line=deck%plate%line, card='PLATE')
    end if
  end subroutine check_equilibrium

  !> The final static state must be one in which no free node is through the
  !> plate (beyond the tolerance) and every contact node pushes (to round-off).
  subroutine check_settled(deck, contact, u, reaction, error)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    real(dp), intent(in) :: u(:), reaction(:)
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: small
    integer :: i, node, z
    small = 0.0_dp
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (contact%active(node)) small = max(small, abs(reaction(node_dof(deck%mesh, node, 2))))
    end do
    small = 1.0e-6_dp*small
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      z = node_dof(deck%mesh, node, 2)
      if ((contact%active(node) .and. reaction(z) < -small) .or. &
          (.not. contact%active(node) .and. contact_gap(deck, contact, u, node) < -contact%tolerance)) then
        call set_error(error, 'the static contact state is not admissible at node '//integer_text(deck%mesh%node_id(node))// &
          ' (r = '//table_real(1.0e3_dp*deck%mesh%xy(1, node))//' mm): '//trim(merge('it pulls on the plate     ', &
          'it is through the plate   ', contact%active(node))), file=deck%cards%file, line=deck%plate%line, card='PLATE')
        return
      end if
    end do
  end subroutine check_settled
end module visco2d_static_contact