!> The CURVE card read into a time history (visco2d_curve): a step, or
!> pairs of time and value with strictly increasing times.
module visco2d_curve_cards
  use visco2d_kinds, only: dp
  use visco2d_ranges, only: time_range, curve_factor_range
  use visco2d_error, only: error_t
  use visco2d_strings, only: integer_text, short_real
  use visco2d_cards, only: card_t, card_deck_t, card_error, positional_word, positional_real, positional_count, &
                           check_fields_used, field_column
  use visco2d_curve, only: curve_t
  implicit none
  private

  public :: read_curve

contains

  !> CURVE name STEP   or   CURVE name t1 v1 t2 v2 ...  (t in s, strictly increasing; v a factor)
  subroutine read_curve(cards, card, curves, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    type(curve_t), allocatable, intent(inout) :: curves(:)
    type(error_t), allocatable, intent(inout) :: error
    type(curve_t) :: curve
    character(:), allocatable :: word
    integer :: k, npoint
    call positional_word(cards, card, 1, 'curve name', curve%name, error); if (allocated(error)) return
    if (verify(curve%name, 'ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_') /= 0 .or. len(curve%name) > 32) then
      call card_error(error, cards, card, 'curve name must be letters, digits or _ (32 at most), got "'// &
                      curve%name//'"', field_column(card, '1')); return
    end if
    do k = 1, size(curves)
      if (curves(k)%name == curve%name) then
        call card_error(error, cards, card, 'curve '//curve%name//' defined twice (first on line '// &
                        integer_text(curves(k)%line)//')', field_column(card, '1')); return
      end if
    end do
    curve%line = card%line
    call positional_word(cards, card, 2, 'STEP or pairs of time (s) and value', word, error)
    if (allocated(error)) return
    if (word == 'STEP') then
      curve%time = [0.0_dp]
      curve%value = [1.0_dp]
    else
      npoint = positional_count(card) - 1
      if (mod(npoint, 2) /= 0) then
        call card_error(error, cards, card, 'CURVE points come in pairs (time value); got '//integer_text(npoint)// &
                        ' numbers (this one has no value)', field_column(card, integer_text(npoint + 1))); return
      end if
      npoint = npoint/2
      allocate(curve%time(npoint), curve%value(npoint))
      do k = 1, npoint
        call positional_real(cards, card, 2*k, 'time of point '//integer_text(k), curve%time(k), error, range=time_range)
        if (allocated(error)) return
        call positional_real(cards, card, 2*k + 1, 'value of point '//integer_text(k), curve%value(k), error, &
                             range=curve_factor_range)
        if (allocated(error)) return
        if (k > 1) then
          if (curve%time(k) <= curve%time(k - 1)) then
            call card_error(error, cards, card, 'curve times must increase strictly (point '//integer_text(k)// &
              ' at t = '//short_real(curve%time(k))//' s)', field_column(card, integer_text(2*k))); return
          end if
        end if
      end do
    end if
    call check_fields_used(cards, card, error, 'CURVE name STEP | CURVE name t1 v1 t2 v2 ...')
    if (allocated(error)) return
    curves = [curves, curve]
  end subroutine read_curve
end module visco2d_curve_cards
