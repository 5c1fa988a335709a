!> A card field that holds a comma-separated list of increasing numbers
!> within a physical range (OUTPUT FIELDS=t1,t2,..., BRUISE THRESHOLDS=v1,v2,...),
!> read with located errors at the field's column.
module visco2d_card_lists
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t
  use visco2d_strings, only: short_real
  use visco2d_ranges, only: range_t, in_range, range_text
  use visco2d_cards, only: card_t, card_deck_t, card_error, parse_real, field_column
  implicit none
  private

  public :: read_increasing_list

contains

  !> The numbers of `list`, the text of field `name` of `card`: each a number
  !> (else "NAME must be a comma-separated list of <description>"), inside
  !> `range` (else "NAME <noun> must be <range>") and larger than the one
  !> before (else "NAME <noun> must increase"). An empty list gives no values.
  subroutine read_increasing_list(cards, card, name, list, description, noun, range, values, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(in) :: card
    character(*), intent(in) :: name, list, description, noun
    type(range_t), intent(in) :: range
    real(dp), allocatable, intent(out) :: values(:)
    type(error_t), allocatable, intent(inout) :: error
    real(dp) :: value
    logical :: ok
    integer :: start, comma
    allocate(values(0))
    start = 1
    do while (start <= len(list))
      comma = index(list(start:), ',')
      if (comma == 0) comma = len(list) - start + 2
      associate (item => list(start:start + comma - 2))
      call parse_real(item, value, ok)
      if (.not. ok) then
        call card_error(error, cards, card, name//' must be a comma-separated list of '//description//', got "'// &
                        item//'"', field_column(card, name)); return
      end if
      if (.not. in_range(value, range)) then
        call card_error(error, cards, card, name//' '//noun//' must be '//range_text(range)//', got "'//item//'"', &
                        field_column(card, name)); return
      end if
      end associate
      if (size(values) > 0) then
        if (value <= values(size(values))) then
          call card_error(error, cards, card, name//' '//noun//' must increase, got '//short_real(value)// &
                          ' after '//short_real(values(size(values))), field_column(card, name)); return
        end if
      end if
      values = [values, value]
      start = start + comma
    end do
  end subroutine read_increasing_list
end module visco2d_card_lists
