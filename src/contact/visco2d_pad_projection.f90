!> The held pairs of a body on a PAD after a step: the inelastic collision
!> of each body node with the pad surface under it.
!>
!> A held body equation c and the pad surface under it obey the
!> multi-point constraint of visco2d_contact,
!>   (C x)_c = x_c - sum_k w_k x_p(k) = g_c,
!> in displacement (g_c: the adjusted value of the step), velocity and
!> acceleration (g_c = 0: the node moves with the surface). After the
!> integrator's update a vector x (the step's dU, U' or U'' at the step's
!> end) misses it by r = C x - g; it is put back by the smallest correction
!> in the mass metric,
!>   x <- x - M^-1 C^T (C M^-1 C^T)^-1 r,
!> the correction a set of equal and opposite impulses on each body node and
!> the surface nodes under it gives. On the velocities this is a perfectly
!> inelastic collision of the pair: it keeps the momentum (sum_k w_k = 1, so
!> the impulses add to zero) and removes the kinetic energy
!>   1/2 r^T (C M^-1 C^T)^-1 r >= 0,
!> so contact can only take energy out. Moving the body node alone onto the
!> surface (the rigid plate's rule, where the plate is immovable) gave the
!> pad's surface node no impulse: a body node caught by a surface node that
!> moves up faster than it was set to the surface's speed, which created
!> kinetic energy at every touch. With a thin soft pad that made the run
!> unstable (the thin-pad case of doc/robustness.md). On the rigid plate
!> (no partners) the correction is the old rule exactly: x_c = g_c.
module visco2d_pad_projection
  use visco2d_kinds, only: dp
  use visco2d_lapack, only: dpotrf, dpotrs
  implicit none
  private

  public :: project_on_surface, pair_compliance

contains

  !> (C M^-1 C^T)_cc = 1/m_c + sum_k w_k^2/m_p(k): the compliance of the pair
  !> of equation c (the body node and the surface nodes under it), 1/mu with
  !> mu the pair's reduced mass; 1/m_c on the rigid plate (no partners).
  pure real(dp) function pair_compliance(partner, weight, mass, c) result(compliance)
    integer, intent(in) :: partner(:, :)
    real(dp), intent(in) :: weight(:, :), mass(:)
    integer, intent(in) :: c
    integer :: k
    compliance = 1.0_dp/mass(c)
    do k = 1, 2
      if (partner(k, c) > 0) compliance = compliance + weight(k, c)**2/mass(partner(k, c))
    end do
  end function pair_compliance

  !> Put the vectors x(:, j) (band order) back on the constraints of the held
  !> equations `rows` (none of them a support) with the values
  !> targets(:, j), by the mass-metric correction of the module header:
  !> x(:, j) <- x(:, j) - M^-1 C^T (C M^-1 C^T)^-1 (C x(:, j) - targets(:, j)).
  !> partner, weight: the constraints' pad equations and weights (visco2d_contact);
  !> mass: the lumped mass of every equation. info > 0: C M^-1 C^T is not
  !> positive definite (two rows the same constraint: cannot happen for
  !> distinct equations; the vectors are then left as they are).
  subroutine project_on_surface(partner, weight, mass, rows, targets, x, info)
    integer, intent(in) :: partner(:, :)
    real(dp), intent(in) :: weight(:, :), mass(:)
    integer, intent(in) :: rows(:)
    real(dp), intent(in) :: targets(:, :)
    real(dp), intent(inout) :: x(:, :)
    integer, intent(out) :: info
    real(dp), allocatable :: matrix(:, :), misfit(:, :)
    integer :: m, i, j, k, l, c, d
    m = size(rows)
    info = 0
    if (m == 0) return
    allocate(matrix(m, m), misfit(m, size(x, 2)))
    ! C M^-1 C^T: row c of C is e_c - sum_k w_k e_p(k); two rows meet on the
    ! equations they share (the same pad node under two body nodes).
    matrix = 0.0_dp
    do i = 1, m
      c = rows(i)
      matrix(i, i) = pair_compliance(partner, weight, mass, c)
      do j = 1, i - 1
        d = rows(j)
        do k = 1, 2
          if (partner(k, c) == 0) cycle
          do l = 1, 2
            if (partner(l, d) == partner(k, c)) &
              matrix(i, j) = matrix(i, j) + weight(k, c)*weight(l, d)/mass(partner(k, c))
          end do
        end do
        matrix(j, i) = matrix(i, j)
      end do
    end do
    do j = 1, size(x, 2)
      do i = 1, m
        misfit(i, j) = constrained(x(:, j), rows(i)) - targets(i, j)
      end do
    end do
    call dpotrf('L', m, matrix, m, info)
    if (info /= 0) return
    call dpotrs('L', m, size(x, 2), matrix, m, misfit, m, info)
    if (info /= 0) return
    do j = 1, size(x, 2)                             ! x <- x - M^-1 C^T lambda
      do i = 1, m
        c = rows(i)
        x(c, j) = x(c, j) - misfit(i, j)/mass(c)
        do k = 1, 2
          if (partner(k, c) > 0) x(partner(k, c), j) = x(partner(k, c), j) + &
                                                       weight(k, c)*misfit(i, j)/mass(partner(k, c))
        end do
      end do
    end do
  contains
    !> (C v)_c = v_c - sum_k w_k v_p(k).
    pure real(dp) function constrained(v, c)
      real(dp), intent(in) :: v(:)
      integer, intent(in) :: c
      integer :: k
      constrained = v(c)
      do k = 1, 2
        if (partner(k, c) > 0) constrained = constrained - weight(k, c)*v(partner(k, c))
      end do
    end function constrained
  end subroutine project_on_surface
end module visco2d_pad_projection
