!> The held system of the static contact path (visco2d_static_contact): the
!> stiffness S and load R assembled once, and for a contact set (the held
!> equations and their values) the two responses u_0 (to the held values)
!> and u_1 (to the full load) whose sum lambda u_1 + u_0 is the state at load
!> factor lambda, with their reactions. On the rigid plate the held
!> equations are eliminated and S refactored; on a PAD they are multi-point
!> constraints in a capacitance system on S factored once with the supports,
!> and a body resting on the pad alone is solved for its rigid translation.
module visco2d_constrained_system
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: integer_text
  use visco2d_deck, only: deck_t
  use visco2d_assembly, only: node_dof, assemble_stiffness, external_load, gravity_load, support_mask, &
                              prescribed_displacement
  use visco2d_banded, only: band_matrix_t, band_constrain_rhs, band_multiply
  use visco2d_factor, only: factor_t, factor_compute, factor_solve_many, factor_solve, solver_of_card, &
                            solve_failure_text
  use visco2d_solve_errors, only: singular_message
  use visco2d_capacitance, only: capacitance_t, capacitance_reset, capacitance_partners, capacitance_set, &
                                 capacitance_apply, constraint_sum
  use visco2d_lapack, only: dgels
  use visco2d_pad_mesh, only: body_nodes
  use visco2d_contact, only: contact_t
  use visco2d_body_mesh, only: contact_card_line, contact_card_name
  implicit none
  private

  public :: constrained_system_t, constrained_system_create, constrained_system_solve

  !> The stiffness and the full load of a static contact problem.
  type :: constrained_system_t
    type(band_matrix_t) :: stiffness             !< S, unconstrained
    real(dp), allocatable :: load(:)             !< loads and gravity
    real(dp), allocatable :: prescribed(:)       !< prescribed support displacements
    logical, allocatable :: supports(:)          !< supported equations
    !> With a PAD: the held equations are multi-point constraints (visco2d_contact),
    !> imposed by a capacitance system on the factor of S with the supports only.
    logical :: pad = .false.
    type(factor_t) :: factor
    type(capacitance_t) :: capacitance
    integer, allocatable :: partner(:, :)        !< (2, n) the constraints' pad equations
    real(dp), allocatable :: weight(:, :)        !< (2, n) and their weights
    !> A body held by the pad alone (its rigid z translation free in S): its
    !> pole's u_z (or, once the pole lifts, another contact node's) is pinned
    !> in the factor (the anchor), the translation `rigid` (1 on the body's z
    !> equations) is an unknown t, and the body's
    !> equilibrium in z closes the system (anchored_solve).
    integer :: anchor = 0                        !< the anchor equation (0: the body has supports of its own)
    real(dp), allocatable :: rigid(:)            !< (n) the body's rigid z translation
    real(dp), allocatable :: anchor_column(:)    !< (n) S^-1 of the anchor constraint's pad part
  end type constrained_system_t

contains

  !> The stiffness S and the full load R (loads and gravity) of a static
  !> contact problem, assembled once for the whole path; with a pad, S
  !> factored once with the supports and the pad's constraints set.
  subroutine constrained_system_create(deck, contact, system, error)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    type(constrained_system_t), intent(out) :: system
    type(error_t), allocatable, intent(out) :: error
    real(dp), allocatable :: shear(:), bulk(:)
    integer :: info
    shear = deck%materials(deck%mesh%element_material)%shear
    bulk = deck%materials(deck%mesh%element_material)%bulk
    call assemble_stiffness(deck%mesh, deck%settings, shear, bulk, system%stiffness)
    system%load = external_load(deck%mesh, deck%settings, deck%loads, 0.0_dp) + &
                  gravity_load(deck%mesh, deck%settings, deck%materials, deck%loads)
    system%supports = support_mask(deck%mesh, deck%settings, deck%loads)
    system%prescribed = prescribed_displacement(deck%mesh, deck%loads, 0.0_dp)
    system%pad = contact%pad
    if (.not. system%pad) return
    system%partner = contact%partner
    system%weight = contact%weight
    ! Whether the body floats is read from its supports, not from the factor:
    ! a singular S is not always caught by the pivot test (on the graded
    ! sphere grid, CHOLMOD's last pivot of the free body passed it, and the
    ! solve of the singular system gave a body out of equilibrium).
    if (floats(deck, system%supports)) then
      call anchor_body(deck, system, node_dof(deck%mesh, contact%pole, 2), info, error)
      if (allocated(error)) return
    else
      call factor_compute(system%factor, system%stiffness, system%supports, info, solver_of_card(deck%settings%solver))
    end if
    if (info > 0) then
      call set_error(error, singular_message(deck%mesh, info)//'; with a PAD the body may rest on the pad '// &
        'alone only if it cannot move otherwise than up and down: fix what else is free', &
        file=deck%cards%file, line=contact_card_line(deck, .true.), &
        card=contact_card_name(deck, .true.))
      return
    end if
    call capacitance_reset(system%capacitance, size(system%load))
    call capacitance_partners(system%capacitance, system%partner, system%weight)
  end subroutine constrained_system_create

  !> Whether the body (the nodes before the pad's) has no supported z
  !> equation, so that its rigid z translation is free in S.
  pure logical function floats(deck, supports)
    type(deck_t), intent(in) :: deck
    logical, intent(in) :: supports(:)
    integer :: node
    floats = .true.
    do node = 1, body_nodes(deck)
      if (supports(node_dof(deck%mesh, node, 2))) floats = .false.
    end do
  end function floats

  !> The body is free (its supports leave it a rigid z translation): pin the
  !> u_z `equation` of one of its contact nodes (the anchor; first the pole)
  !> and refactor; the translation and the anchor constraint's pad column for
  !> anchored_solve. info > 0: still singular; `error` if the solve failed.
  subroutine anchor_body(deck, system, equation, info, error)
    type(deck_t), intent(in) :: deck
    type(constrained_system_t), intent(inout) :: system
    integer, intent(in) :: equation
    integer, intent(out) :: info
    type(error_t), allocatable, intent(inout) :: error
    integer :: node, k, status
    system%anchor = equation
    call factor_compute(system%factor, system%stiffness, system%supports .or. equation_mask(system%anchor), info, &
                        solver_of_card(deck%settings%solver))
    if (info > 0) return
    if (.not. allocated(system%rigid)) then             ! the body's z translation (no z supports: it floats)
      allocate(system%rigid(size(system%load)))
      system%rigid = 0.0_dp
      do node = 1, body_nodes(deck)
        system%rigid(node_dof(deck%mesh, node, 2)) = 1.0_dp
      end do
    end if
    if (.not. allocated(system%anchor_column)) allocate(system%anchor_column(size(system%load)))
    system%anchor_column = 0.0_dp                       ! the anchor constraint's pad part: -sum w e_p
    do k = 1, 2
      if (system%partner(k, system%anchor) > 0) &
        system%anchor_column(system%partner(k, system%anchor)) = -system%weight(k, system%anchor)
    end do
    call factor_solve(system%factor, system%anchor_column, status)
    if (status /= 0) call set_error(error, solve_failure_text(status))
  contains
    !> The mask of one equation.
    function equation_mask(equation) result(mask)
      integer, intent(in) :: equation
      logical :: mask(size(system%load))
      mask = .false.
      mask(equation) = .true.
    end function equation_mask
  end subroutine anchor_body

  !> With the supports and the `held` equations fixed: u_1, the response to
  !> the full load and prescribed support displacements (held values 0), and
  !> u_0, the response to the held values alone (no load), with their
  !> reactions S u - R. The state at load factor lambda is u_0 + lambda u_1.
  subroutine constrained_system_solve(deck, system, held, values, base, rate, reaction_base, reaction_rate, error)
    type(deck_t), intent(in) :: deck
    type(constrained_system_t), intent(inout) :: system
    logical, intent(in) :: held(:)
    real(dp), intent(in) :: values(:)
    real(dp), allocatable, intent(out) :: base(:), rate(:), reaction_base(:), reaction_rate(:)
    type(error_t), allocatable, intent(out) :: error
    if (system%pad) then
      call pad_system_solve(deck, system, held, values, base, rate, error)
    else
      call eliminated_solve(deck, system, held, values, base, rate, error)
    end if
    if (allocated(error)) return
    reaction_rate = band_multiply(system%stiffness, rate) - system%load
    reaction_base = band_multiply(system%stiffness, base)
  end subroutine constrained_system_solve

  !> constrained_system_solve on the rigid plate: the held equations eliminated and
  !> S refactored with them fixed.
  subroutine eliminated_solve(deck, system, held, values, base, rate, error)
    type(deck_t), intent(in) :: deck
    type(constrained_system_t), intent(in) :: system
    logical, intent(in) :: held(:)
    real(dp), intent(in) :: values(:)
    real(dp), allocatable, intent(out) :: base(:), rate(:)
    type(error_t), allocatable, intent(out) :: error
    integer :: status
    type(factor_t) :: factor
    real(dp), allocatable :: rhs(:, :)
    logical, allocatable :: fixed(:)
    integer :: info
    fixed = system%supports .or. held
    call factor_compute(factor, system%stiffness, fixed, info, solver_of_card(deck%settings%solver))
    if (info > 0) then
      call set_error(error, singular_message(deck%mesh, info), file=deck%cards%file)
      return
    end if
    allocate(rhs(size(values), 2))
    rhs(:, 1) = system%load
    call band_constrain_rhs(system%stiffness, fixed, merge(0.0_dp, system%prescribed, held), rhs(:, 1))
    rhs(:, 2) = 0.0_dp
    call band_constrain_rhs(system%stiffness, fixed, merge(values, 0.0_dp, held), rhs(:, 2))
    call factor_solve_many(factor, rhs, status)
    if (status /= 0) then
      call set_error(error, solve_failure_text(status))
      return
    end if
    rate = rhs(:, 1)
    base = rhs(:, 2)
  end subroutine eliminated_solve

  !> constrained_system_solve with a pad: the held equations are constraints
  !> u_c - sum w u_p = value imposed by the capacitance system on S's factor
  !> with the supports (visco2d_capacitance): u_1 from the load and the
  !> prescribed supports (held values 0), u_0 from the held values alone.
  subroutine pad_system_solve(deck, system, held, values, base, rate, error)
    type(deck_t), intent(in) :: deck
    type(constrained_system_t), intent(inout) :: system
    logical, intent(in) :: held(:)
    real(dp), intent(in) :: values(:)
    real(dp), allocatable, intent(out) :: base(:), rate(:)
    type(error_t), allocatable, intent(out) :: error
    integer :: info, status
    logical, allocatable :: free_held(:)
    free_held = held .and. .not. system%supports
    if (system%anchor > 0) then
      if (.not. held(system%anchor)) call move_anchor(deck, system, held, error)
      if (allocated(error)) return
      free_held(system%anchor) = .false.
    end if
    call capacitance_set(system%capacitance, system%factor, free_held, info, error)
    if (allocated(error)) return
    if (info > 0) then
      call set_error(error, 'the contact capacitance matrix is not positive definite (equation '//integer_text(info)// &
                     ' of the held set)', file=deck%cards%file, line=contact_card_line(deck, .true.), &
        card=contact_card_name(deck, .true.))
      return
    end if
    if (system%anchor > 0) then
      call anchored_solve(deck, system, values, base, rate, error)
      return
    end if
    rate = system%load
    call band_constrain_rhs(system%stiffness, system%supports, system%prescribed, rate)
    call factor_solve(system%factor, rate, status)
    if (status /= 0) then
      call set_error(error, solve_failure_text(status))
      return
    end if
    call capacitance_apply(system%capacitance, spread(0.0_dp, 1, size(values)), rate)
    allocate(base(size(values)))
    base = 0.0_dp
    call capacitance_apply(system%capacitance, values, base)
  end subroutine pad_system_solve

  !> The anchor's node has left the pad (a body resting on the pad alone whose
  !> pole lifts, e.g. under a stiff cover with STICK): pin instead the held
  !> body z equation of the node nearest the axis, refactor, and start the
  !> capacitance system again on the new factor. No held body z equation:
  !> the body would be free, an error at the PAD card.
  subroutine move_anchor(deck, system, held, error)
    type(deck_t), intent(in) :: deck
    type(constrained_system_t), intent(inout) :: system
    logical, intent(in) :: held(:)
    type(error_t), allocatable, intent(out) :: error
    integer :: node, equation, chosen, info
    real(dp) :: nearest
    chosen = 0
    nearest = huge(1.0_dp)
    do node = 1, body_nodes(deck)
      equation = node_dof(deck%mesh, node, 2)
      if (.not. held(equation) .or. system%supports(equation)) cycle
      if (abs(deck%mesh%xy(1, node)) < nearest) then
        nearest = abs(deck%mesh%xy(1, node))
        chosen = equation
      end if
    end do
    if (chosen == 0) then
      call set_error(error, 'the body has lifted off the pad, which alone holds it: it would be free', &
                     file=deck%cards%file, line=contact_card_line(deck, .true.), &
        card=contact_card_name(deck, .true.))
      return
    end if
    call anchor_body(deck, system, chosen, info, error)
    if (allocated(error)) return
    if (info > 0) then
      call set_error(error, singular_message(deck%mesh, info)//' (the body resting on the pad, anchored at another '// &
                     'contact node)', file=deck%cards%file, line=contact_card_line(deck, .true.), &
        card=contact_card_name(deck, .true.))
      return
    end if
    call capacitance_reset(system%capacitance, size(system%load))
    call capacitance_partners(system%capacitance, system%partner, system%weight)
  end subroutine move_anchor

  !> u_0 and u_1 of a body resting on the pad alone. With the anchor (a held
  !> node's u_z, first the pole's) pinned, u = w + Z lambda + z_a lambda_a + t phi, where w =
  !> S_a^-1 f, Z the capacitance columns of the other held equations, z_a the
  !> anchor constraint's pad column, phi the body's rigid translation (S phi =
  !> 0) and t its amount. The unknowns lambda, lambda_a, t solve (dense,
  !> m + 2 equations): the held constraints c_i^T u = g_i, the anchor's
  !> t - sum w_a u_p = g_a, and the body's equilibrium in z, phi^T (f + sum
  !> c lambda) = 0, i.e. lambda_a + sum over the z constraints lambda_i = -phi^T f.
  subroutine anchored_solve(deck, system, values, base, rate, error)
    type(deck_t), intent(in) :: deck
    type(constrained_system_t), intent(in) :: system
    real(dp), intent(in) :: values(:)
    real(dp), allocatable, intent(out) :: base(:), rate(:)
    type(error_t), allocatable, intent(out) :: error
    integer :: status
    real(dp), allocatable :: w(:), fixed_values(:)
    logical, allocatable :: fixed(:)
    fixed = system%supports
    fixed(system%anchor) = .true.
    fixed_values = merge(0.0_dp, system%prescribed, fixed .and. .not. system%supports)
    w = system%load                                    ! u_1: the load and the prescribed supports, held values 0
    call band_constrain_rhs(system%stiffness, fixed, fixed_values, w)
    call factor_solve(system%factor, w, status)
    if (status /= 0) then
      call set_error(error, solve_failure_text(status))
      return
    end if
    rate = bordered_solution(w, system%load, spread(0.0_dp, 1, size(values)))
    if (allocated(error)) return
    w = 0.0_dp                                         ! u_0: the held values alone
    base = bordered_solution(w, spread(0.0_dp, 1, size(values)), values)
  contains
    !> u for w = S_a^-1 f, the load f and the held values g.
    function bordered_solution(w, f, g) result(u)
      real(dp), intent(in) :: w(:), f(:), g(:)
      real(dp), allocatable :: u(:), matrix(:, :), right(:), work(:)
      integer :: m, i, j, k, info, equation
      associate (cap => system%capacitance, a => system%anchor)
      m = size(cap%held)
      allocate(matrix(m + 2, m + 2), right(m + 2), work(64*(m + 2)))
      matrix = 0.0_dp
      do i = 1, m
        equation = cap%held(i)
        do j = 1, m
          matrix(i, j) = constrained_value(cap%columns(:, cap%slot(j)), equation)
        end do
        matrix(i, m + 1) = constrained_value(system%anchor_column, equation)
        matrix(i, m + 2) = constrained_value(system%rigid, equation)
        right(i) = g(equation) - constrained_value(w, equation)
      end do
      do j = 1, m                                       ! the anchor: t - sum w_a (w + Z lambda + z_a lambda_a)_p = g_a
        matrix(m + 1, j) = -constraint_sum(system%partner, system%weight, cap%columns(:, cap%slot(j)), a)
      end do
      matrix(m + 1, m + 1) = -constraint_sum(system%partner, system%weight, system%anchor_column, a)
      matrix(m + 1, m + 2) = 1.0_dp
      right(m + 1) = g(a) + constraint_sum(system%partner, system%weight, w, a)
      do j = 1, m                                       ! equilibrium in z: lambda_a + sum phi^T c_j lambda_j = -phi^T f
        matrix(m + 2, j) = constrained_value(system%rigid, cap%held(j))
      end do
      matrix(m + 2, m + 1) = 1.0_dp
      right(m + 2) = -dot_product(system%rigid, f)
      call dgels('N', m + 2, m + 2, 1, matrix, m + 2, right, m + 2, work, size(work), info)
      if (info /= 0) then
        call set_error(error, 'the contact system of the body resting on the pad is singular', &
                       file=deck%cards%file, line=contact_card_line(deck, .true.), &
        card=contact_card_name(deck, .true.))
        u = w
        return
      end if
      u = w + right(m + 1)*system%anchor_column + right(m + 2)*system%rigid
      do k = 1, m
        u = u + right(k)*cap%columns(:, cap%slot(k))
      end do
      end associate
    end function bordered_solution

    !> c_i^T x of the constraint of `equation`: x(equation) - sum w x(partner).
    real(dp) function constrained_value(x, equation)
      real(dp), intent(in) :: x(:)
      integer, intent(in) :: equation
      constrained_value = x(equation) - constraint_sum(system%partner, system%weight, x, equation)
    end function constrained_value
  end subroutine anchored_solve
end module visco2d_constrained_system
