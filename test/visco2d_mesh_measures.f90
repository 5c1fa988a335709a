!> Shape measures of a generated mesh for the grid tests (test_sphere_grid,
!> test_spheroid): interior angles, corner Jacobians and the volume of
!> revolution, computed from the nodes alone (independently of the generator).
module visco2d_mesh_measures
  use visco2d_kinds, only: dp, pi
  implicit none
  private

  public :: shape_measures

contains

  !> Smallest and largest interior angle (deg), least corner Jacobian (the
  !> cross product of the two sides at a corner, m^2) and the volume of
  !> revolution (each quadrilateral as two triangles, 2 pi area r_centroid).
  pure subroutine shape_measures(xy, connectivity, smallest, largest, least_jacobian, volume)
    real(dp), intent(in) :: xy(:, :)
    integer, intent(in) :: connectivity(:, :)
    real(dp), intent(out) :: smallest, largest, least_jacobian, volume
    real(dp) :: p(2, 4), before(2), after(2), cross, angle
    integer :: e, c
    smallest = 180.0_dp
    largest = 0.0_dp
    least_jacobian = huge(1.0_dp)
    volume = 0.0_dp
    do e = 1, size(connectivity, 2)
      p = xy(:, connectivity(:, e))
      do c = 1, 4
        after = p(:, mod(c, 4) + 1) - p(:, c)
        before = p(:, mod(c + 2, 4) + 1) - p(:, c)
        cross = after(1)*before(2) - after(2)*before(1)
        angle = atan2(abs(cross), dot_product(after, before))*180.0_dp/pi
        smallest = min(smallest, angle)
        largest = max(largest, angle)
        least_jacobian = min(least_jacobian, cross)
      end do
      volume = volume + triangle_volume(p(:, 1), p(:, 2), p(:, 3)) + triangle_volume(p(:, 1), p(:, 3), p(:, 4))
    end do
  end subroutine shape_measures

  pure real(dp) function triangle_volume(a, b, c)
    real(dp), intent(in) :: a(2), b(2), c(2)
    triangle_volume = pi*((b(1) - a(1))*(c(2) - a(2)) - (c(1) - a(1))*(b(2) - a(2)))*(a(1) + b(1) + c(1))/3.0_dp
  end function triangle_volume
end module visco2d_mesh_measures
