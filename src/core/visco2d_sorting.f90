!> Stable sorting, once for the whole program: `sorted_order(keys)` is the
!> permutation that puts the keys in ascending order, equal keys in their
!> given order (so a sort by degree, radius or rate never reorders ties, and
!> the renumbering, the pressure table and the Prony terms come out the same
!> on every machine). A bottom-up merge sort, n log n comparisons.
!>
!> Integer keys (default or 64-bit) are compared as integers, real keys
!> through an order-preserving map onto 64-bit integers (their IEEE bits,
!> negative values with all but the sign bit flipped; -0 counts as +0), and
!> names by Fortran's character comparison (trailing blanks ignored).
module visco2d_sorting
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp
  implicit none
  private

  public :: sorted_order

  !> The stable ascending order of integer, 64-bit integer, real or character keys.
  interface sorted_order
    module procedure order_of_int64, order_of_integers, order_of_reals, order_of_names
  end interface sorted_order

contains

  !> Stable ascending order of 64-bit integer keys (bottom-up merge sort).
  pure function order_of_int64(keys) result(order)
    integer(int64), intent(in) :: keys(:)
    integer, allocatable :: order(:)
    integer, allocatable :: work(:)
    integer :: n, width, left, middle, right, i, j, k
    n = size(keys)
    allocate(order(n), work(n))
    order = [(i, i = 1, n)]
    width = 1
    do while (width < n)
      left = 1
      do while (left <= n)
        middle = min(left + width - 1, n)
        right = min(left + 2*width - 1, n)
        i = left
        j = middle + 1
        do k = left, right
          if (j > right) then
            work(k) = order(i); i = i + 1
          else if (i > middle) then
            work(k) = order(j); j = j + 1
          else if (keys(order(j)) < keys(order(i))) then
            work(k) = order(j); j = j + 1
          else
            work(k) = order(i); i = i + 1
          end if
        end do
        left = left + 2*width
      end do
      order = work
      width = 2*width
    end do
  end function order_of_int64

  !> Stable ascending order of default integer keys.
  pure function order_of_integers(keys) result(order)
    integer, intent(in) :: keys(:)
    integer, allocatable :: order(:)
    order = order_of_int64(int(keys, int64))
  end function order_of_integers

  !> Stable ascending order of real keys (not NaN), through ordered_bits.
  pure function order_of_reals(keys) result(order)
    real(dp), intent(in) :: keys(:)
    integer, allocatable :: order(:)
    order = order_of_int64(ordered_bits(keys))
  end function order_of_reals

  !> 64-bit integers in the order of the reals: the IEEE bits of x (+0 for -0),
  !> and for a negative x the bits with all but the sign flipped, so that a
  !> larger magnitude gives a smaller integer.
  elemental integer(int64) function ordered_bits(x) result(key)
    real(dp), intent(in) :: x
    if (x == 0.0_dp) then
      key = 0_int64
    else
      key = transfer(x, 0_int64)
      if (key < 0_int64) key = ieor(key, huge(0_int64))
    end if
  end function ordered_bits

  !> Stable ascending order of names (bottom-up merge sort on character keys).
  pure function order_of_names(names) result(order)
    character(*), intent(in) :: names(:)
    integer, allocatable :: order(:)
    integer, allocatable :: work(:)
    integer :: n, width, left, middle, right, i, j, k
    n = size(names)
    allocate(order(n), work(n))
    order = [(i, i = 1, n)]
    width = 1
    do while (width < n)
      left = 1
      do while (left <= n)
        middle = min(left + width - 1, n)
        right = min(left + 2*width - 1, n)
        i = left
        j = middle + 1
        do k = left, right
          if (j > right) then
            work(k) = order(i); i = i + 1
          else if (i > middle) then
            work(k) = order(j); j = j + 1
          else if (names(order(j)) < names(order(i))) then
            work(k) = order(j); j = j + 1
          else
            work(k) = order(i); i = i + 1
          end if
        end do
        left = left + 2*width
      end do
      order = work
      width = 2*width
    end do
  end function order_of_names
end module visco2d_sorting
