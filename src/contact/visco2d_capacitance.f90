!> Contact conditions without refactoring: the capacitance (Schur-complement)
!> method. S~ is factored once per time step size with the supports only;
!> the m equations held by the plate (u_c = g) are then imposed on its
!> solution w = S~^-1 f through
!>   C lambda = g - w_c,    C = E^T S~^-1 E  (m x m, E: the unit columns e_c),
!>   u = w + S~^-1 E lambda,
!> which is exactly the solution of S~ with those equations eliminated
!> (rows and columns zeroed, values moved to the right-hand side): on the
!> free rows S~ u = f + E lambda = f. lambda is the force the plate needs.
!> The columns z_c = S~^-1 e_c cost one back-substitution each and are kept
!> (per equation, reused when a node leaves and comes back) until S~
!> changes; C is refactored (dense Cholesky, m^3/3) when the set changes.
!> A node touching thus costs one back-substitution (visco2d_factor) instead
!> of a refactorization of S~; each apply adds Z lambda in one pass (dgemv).
!>
!> With a pad the held equation c is a multi-point constraint
!>   u_c - sum_k w_k u_p(k) = value_c
!> (a body node on the pad's surface segment, nodes p(1), p(2)): the unit
!> column e_c becomes c = e_c - sum_k w_k e_p(k), and everything above holds
!> with E = [c ...]: C = E^T S~^-1 E, u = w + S~^-1 E lambda; lambda acts
!> on the body node and, with the weights, equal and opposite on the pad.
!> The constraints are set once (`capacitance_partners`): they follow the
!> undeformed positions, so the kept columns stay valid.
module visco2d_capacitance
  use visco2d_kinds, only: dp
  use visco2d_lapack, only: dpotrf, dpotrs, dgemv
  use visco2d_factor, only: factor_t, factor_solve_many, solve_failure_text
  use visco2d_error, only: error_t, set_error
  implicit none
  private

  public :: capacitance_t, capacitance_reset, capacitance_set, capacitance_apply, capacitance_partners, &
            constraint_sum

  !> The kept columns of S~^-1 and the factored capacitance matrix of the
  !> current set of held equations.
  type :: capacitance_t
    integer :: n = 0                       !< order of S~
    real(dp), allocatable :: columns(:, :) !< (n, capacity): z = S~^-1 e_c, one per equation ever held
    integer, allocatable :: column_of(:)   !< (n): column of equation c in `columns` (0: none yet)
    integer :: stored = 0                  !< columns in use
    integer, allocatable :: held(:)        !< (m) the held equations, in order
    integer, allocatable :: slot(:)        !< (m) their columns
    real(dp), allocatable :: matrix(:, :)  !< (m, m) Cholesky factor of C
    real(dp), allocatable :: multiplier(:) !< (m) lambda of the last apply
    real(dp), allocatable :: weights(:)    !< (capacity) lambda by column of `columns` (0: not held)
    integer, allocatable :: partner(:, :)  !< (2, n) equations of the other end of equation c's constraint (0: none)
    real(dp), allocatable :: weight(:, :)  !< (2, n) their weights
    integer :: factorizations = 0          !< dense factorizations of C
    integer :: solves = 0                  !< back-substitutions with S~ for new columns
  end type capacitance_t

contains

  !> Forget every column (S~ has changed): order n, nothing held.
  subroutine capacitance_reset(capacitance, n)
    type(capacitance_t), intent(inout) :: capacitance
    integer, intent(in) :: n
    capacitance%n = n
    if (allocated(capacitance%columns)) then
      if (size(capacitance%columns, 1) /= n) deallocate(capacitance%columns)
    end if
    if (allocated(capacitance%column_of)) then
      if (size(capacitance%column_of) /= n) deallocate(capacitance%column_of)
    end if
    if (.not. allocated(capacitance%column_of)) allocate(capacitance%column_of(n))
    capacitance%column_of = 0
    capacitance%stored = 0
    capacitance%held = [integer ::]
    capacitance%slot = [integer ::]
    if (allocated(capacitance%matrix)) deallocate(capacitance%matrix)
    allocate(capacitance%matrix(0, 0))
    capacitance%multiplier = [real(dp) ::]
    capacitance%weights = [real(dp) ::]
  end subroutine capacitance_reset

  !> The multi-point constraints of a pad: equation c, when held, keeps
  !> u_c - sum_k weight(k, c) u_partner(k, c) at its value (partner 0: none).
  !> Kept over resets.
  subroutine capacitance_partners(capacitance, partner, weight)
    type(capacitance_t), intent(inout) :: capacitance
    integer, intent(in) :: partner(:, :)
    real(dp), intent(in) :: weight(:, :)
    capacitance%partner = partner
    capacitance%weight = weight
  end subroutine capacitance_partners

  !> c_i^T x for the constraint of equation c: x(c) - sum_k w_k x(p_k).
  pure real(dp) function constrained(capacitance, x, c) result(value)
    type(capacitance_t), intent(in) :: capacitance
    real(dp), intent(in) :: x(:)
    integer, intent(in) :: c
    value = x(c) - partner_part(capacitance, x, c)
  end function constrained

  !> sum_k w_k x(p_k) of equation c's constraint (0: a plain equation).
  pure real(dp) function partner_part(capacitance, x, c) result(value)
    type(capacitance_t), intent(in) :: capacitance
    real(dp), intent(in) :: x(:)
    integer, intent(in) :: c
    value = 0.0_dp
    if (allocated(capacitance%partner)) value = constraint_sum(capacitance%partner, capacitance%weight, x, c)
  end function partner_part

  !> sum_k weight(k, c) x(partner(k, c)) over the partners of equation c
  !> (partner 0: none): the other end of its multi-point constraint.
  pure real(dp) function constraint_sum(partner, weight, x, c) result(value)
    integer, intent(in) :: partner(:, :)
    real(dp), intent(in) :: weight(:, :), x(:)
    integer, intent(in) :: c
    integer :: k
    value = 0.0_dp
    do k = 1, 2
      if (partner(k, c) > 0) value = value + weight(k, c)*x(partner(k, c))
    end do
  end function constraint_sum

  !> Hold the equations with held(c) (none of them a support of `factor`):
  !> compute the missing columns with `factor` and factor C. info > 0 if C
  !> is not positive definite (the held set is dependent: cannot happen for
  !> distinct unsupported equations of a positive definite S~); `error` if a
  !> solve with the factor failed (factor_solve_many).
  subroutine capacitance_set(capacitance, factor, held, info, error)
    type(capacitance_t), intent(inout) :: capacitance
    type(factor_t), intent(in) :: factor
    logical, intent(in) :: held(:)
    integer, intent(out) :: info
    type(error_t), allocatable, intent(inout) :: error
    integer :: i, j, c, m
    info = 0
    capacitance%held = pack([(c, c = 1, capacitance%n)], held)
    m = size(capacitance%held)
    if (allocated(capacitance%slot)) deallocate(capacitance%slot)
    allocate(capacitance%slot(m))
    call add_columns(capacitance, factor, pack(capacitance%held, capacitance%column_of(capacitance%held) == 0), error)
    if (allocated(error)) return
    do i = 1, m
      capacitance%slot(i) = capacitance%column_of(capacitance%held(i))
    end do
    if (allocated(capacitance%matrix)) deallocate(capacitance%matrix)
    allocate(capacitance%matrix(m, m))
    do j = 1, m
      do i = 1, m
        capacitance%matrix(i, j) = constrained(capacitance, capacitance%columns(:, capacitance%slot(j)), &
                                               capacitance%held(i))
      end do
    end do
    if (allocated(capacitance%multiplier)) deallocate(capacitance%multiplier)
    allocate(capacitance%multiplier(m))
    capacitance%multiplier = 0.0_dp
    if (m == 0) return
    call dpotrf('L', m, capacitance%matrix, m, info)
    capacitance%factorizations = capacitance%factorizations + 1
  end subroutine capacitance_set

  !> Given w = S~^-1 f (supports imposed), impose u_c = values(c) on the held
  !> equations: w <- w + S~^-1 E lambda with C lambda = values_c - w_c.
  subroutine capacitance_apply(capacitance, values, w)
    type(capacitance_t), intent(inout) :: capacitance
    real(dp), intent(in) :: values(:)
    real(dp), intent(inout), contiguous :: w(:)
    integer :: i, m, info
    m = size(capacitance%held)
    if (m == 0) return
    do i = 1, m
      capacitance%multiplier(i) = values(capacitance%held(i)) - constrained(capacitance, w, capacitance%held(i))
    end do
    call dpotrs('L', m, 1, capacitance%matrix, m, capacitance%multiplier, m, info)
    if (size(capacitance%weights) /= size(capacitance%columns, 2)) then
      deallocate(capacitance%weights)
      allocate(capacitance%weights(size(capacitance%columns, 2)))
    end if
    capacitance%weights = 0.0_dp
    capacitance%weights(capacitance%slot) = capacitance%multiplier
    call dgemv('N', capacitance%n, capacitance%stored, 1.0_dp, capacitance%columns, capacitance%n, &
               capacitance%weights, 1, 1.0_dp, w, 1)           ! w += Z lambda, one pass over the columns
    do i = 1, m                                         ! exactly on the constraint, not to round-off
      w(capacitance%held(i)) = values(capacitance%held(i)) + partner_part(capacitance, w, capacitance%held(i))
    end do
  end subroutine capacitance_apply

  !> z = S~^-1 e_c for each new equation c, as new columns, in one
  !> multi-right-hand-side back-substitution (the store doubles when full).
  subroutine add_columns(capacitance, factor, new, error)
    type(capacitance_t), intent(inout) :: capacitance
    type(factor_t), intent(in) :: factor
    integer, intent(in) :: new(:)
    type(error_t), allocatable, intent(inout) :: error
    real(dp), allocatable :: grown(:, :)
    integer :: capacity, first, last, k, j, status
    if (size(new) == 0) return
    capacity = 0
    if (allocated(capacitance%columns)) capacity = size(capacitance%columns, 2)
    if (capacitance%stored + size(new) > capacity) then
      allocate(grown(capacitance%n, max(8, 2*capacity, capacitance%stored + size(new))))
      if (capacitance%stored > 0) grown(:, 1:capacitance%stored) = capacitance%columns(:, 1:capacitance%stored)
      call move_alloc(grown, capacitance%columns)
    end if
    first = capacitance%stored + 1
    last = capacitance%stored + size(new)
    capacitance%columns(:, first:last) = 0.0_dp
    do k = 1, size(new)
      capacitance%columns(new(k), first + k - 1) = 1.0_dp
      if (allocated(capacitance%partner)) then         ! c = e_c - sum w e_p
        do j = 1, 2
          if (capacitance%partner(j, new(k)) > 0) capacitance%columns(capacitance%partner(j, new(k)), first + k - 1) = &
            -capacitance%weight(j, new(k))
        end do
      end if
      capacitance%column_of(new(k)) = first + k - 1
    end do
    call factor_solve_many(factor, capacitance%columns(:, first:last), status)
    if (status /= 0) then
      call set_error(error, solve_failure_text(status))
      return
    end if
    capacitance%stored = last
    capacitance%solves = capacitance%solves + size(new)
  end subroutine add_columns
end module visco2d_capacitance
