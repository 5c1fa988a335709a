!> visco2d_sorting's stable order against its definition, checked pair by
!> pair: for every k, keys(order(k)) <= keys(order(k+1)), and order(k) <
!> order(k+1) where the two keys are equal (stability); order a permutation.
!> Random keys of many sizes (0, 1, 2, odd, powers of two and beyond) with
!> many ties, negative reals, -0 beside +0 (equal: kept in their order),
!> 64-bit keys beyond 2^53 that differ in their last bit, names with
!> trailing blanks (equal to the shorter name), and the insertion sort the
!> sites used before (equal permutations: the order of ties is unchanged).
program test_sorting
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp
  use visco2d_sorting, only: sorted_order
  use visco2d_testing, only: check, test_summary
  implicit none
  integer, parameter :: sizes(*) = [0, 1, 2, 3, 7, 16, 17, 64, 100, 1000, 4097]
  integer :: s

  do s = 1, size(sizes)
    call random_reals(sizes(s))
    call random_integers(sizes(s))
  end do
  call signed_zero_and_negatives()
  call large_int64()
  call names()
  call test_summary('test_sorting')

contains

  logical function is_permutation(order, n)
    integer, intent(in) :: order(:), n
    logical :: seen(n)
    integer :: k
    seen = .false.
    is_permutation = size(order) == n
    if (.not. is_permutation) return
    do k = 1, n
      if (order(k) < 1 .or. order(k) > n) then
        is_permutation = .false.
        return
      end if
      seen(order(k)) = .true.
    end do
    is_permutation = all(seen)
  end function is_permutation

  logical function stable_real(keys, order) result(ok)
    real(dp), intent(in) :: keys(:)
    integer, intent(in) :: order(:)
    integer :: k
    ok = is_permutation(order, size(keys))
    do k = 1, size(order) - 1
      if (.not. ok) return
      ok = keys(order(k)) <= keys(order(k + 1))
      if (ok .and. keys(order(k)) == keys(order(k + 1))) ok = order(k) < order(k + 1)
    end do
  end function stable_real

  !> The insertion sort of the old sites (x(j) <= value stops the shift: stable).
  function insertion_order(keys) result(order)
    real(dp), intent(in) :: keys(:)
    integer, allocatable :: order(:)
    integer :: i, j, swap
    order = [(i, i = 1, size(keys))]
    do i = 2, size(order)
      j = i
      do while (j > 1)
        if (keys(order(j - 1)) <= keys(order(j))) exit
        swap = order(j); order(j) = order(j - 1); order(j - 1) = swap
        j = j - 1
      end do
    end do
  end function insertion_order

  subroutine random_reals(n)
    integer, intent(in) :: n
    real(dp) :: keys(n)
    integer, allocatable :: order(:)
    character(len=16) :: tag
    write(tag, '(i0)') n
    call random_number(keys)
    keys = real(nint(20.0_dp*keys) - 10, dp)*0.37_dp        ! 21 values, many ties, negatives
    order = sorted_order(keys)
    call check('reals_sorted_stable_n'//trim(tag), stable_real(keys, order))
    call check('reals_as_insertion_sort_n'//trim(tag), all(order == insertion_order(keys)))
  end subroutine random_reals

  subroutine random_integers(n)
    integer, intent(in) :: n
    real(dp) :: draw(n)
    integer :: keys(n)
    integer, allocatable :: order(:)
    character(len=16) :: tag
    write(tag, '(i0)') n
    call random_number(draw)
    keys = nint(7.0_dp*draw) - 3
    order = sorted_order(keys)
    call check('integers_sorted_stable_n'//trim(tag), stable_real(real(keys, dp), order))
  end subroutine random_integers

  subroutine signed_zero_and_negatives()
    real(dp) :: keys(7)
    integer, allocatable :: order(:)
    keys = [0.0_dp, -0.0_dp, -1.0e-300_dp, -huge(1.0_dp), 1.0e-300_dp, huge(1.0_dp), -0.0_dp]
    order = sorted_order(keys)
    call check('reals_extremes_order', all(order == [4, 3, 1, 2, 7, 5, 6]))
  end subroutine signed_zero_and_negatives

  subroutine large_int64()
    integer(int64) :: keys(4)
    integer, allocatable :: order(:)
    keys = [2_int64**60 + 1, 2_int64**60, -2_int64**60, 2_int64**60 + 1]
    order = sorted_order(keys)
    call check('int64_last_bit', all(order == [3, 2, 1, 4]))
  end subroutine large_int64

  subroutine names()
    character(len=8) :: keys(5)
    integer, allocatable :: order(:)
    keys = [character(len=8) :: 'peach', 'apple', 'pear', 'apple', 'apple_2']
    order = sorted_order(keys)
    call check('names_stable', all(order == [2, 4, 5, 1, 3]))
    order = sorted_order([character(len=3) :: 'b', 'a', 'a  '])
    call check('names_trailing_blanks_equal', all(order == [2, 3, 1]))
  end subroutine names
end program test_sorting
