!> The errors of a failed solve of the base, located in the deck: a
!> singular stiffness (the node, its component and the card of an element
!> holding it), an out-of-balance solution (check_balance), a result that is
!> not finite. Used by the static and quasi-static solutions and, for the
!> same failures, by the contact and dynamic extensions.
module visco2d_solve_errors
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: itoa
  use visco2d_deck, only: deck_t
  implicit none
  private

  public :: check_balance, singular_message, singular_error, node_text, card_at_line, not_finite_error

contains

  !> A solve of a singular stiffness can pass the factor's pivot test (a body
  !> with no support along z: its rigid translation) and return a huge,
  !> meaningless displacement. Then the free equations are out of balance:
  !> the residual K u - R there, round-off for a true solution, is above
  !> 1e-8 of the loads and the support reactions. That is the singular-
  !> stiffness error, at the worst equation.
  subroutine check_balance(deck, residual, fixed, load, error)
    type(deck_t), intent(in) :: deck
    real(dp), intent(in) :: residual(:), load(:)
    logical, intent(in) :: fixed(:)
    type(error_t), allocatable, intent(inout) :: error
    real(dp) :: scale
    integer :: worst
    scale = max(maxval(abs(load)), maxval(abs(merge(residual, 0.0_dp, fixed))), tiny(1.0_dp))
    worst = maxloc(abs(merge(0.0_dp, residual, fixed)), dim=1)
    if (abs(residual(worst)) > 1.0e-8_dp*scale .and. .not. fixed(worst)) call singular_error(deck, worst, error)
  end subroutine check_balance

  !> Message for a factorization failure at band equation `equation`.
  function singular_message(deck, equation) result(message)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: equation
    character(:), allocatable :: message
    message = 'the stiffness matrix is singular or not positive definite'//node_text(deck, equation)// &
      ': the body can probably move freely (a rigid-body mode); add FIX cards'// &
      ' that stop it, or check the material constants'
  end function singular_message

  !> The error of a static factorization failure at band equation `equation`,
  !> located at the card that defined an element holding that node.
  subroutine singular_error(deck, equation, error)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: equation
    type(error_t), allocatable, intent(inout) :: error
    integer :: line
    line = equation_line(deck, equation)
    call set_error(error, singular_message(deck, equation), file=deck%cards%file, line=line, &
                   card=card_at_line(deck, line))
  end subroutine singular_error

  !> ' at node N (u_z)' for band equation `equation` ('' if not found).
  function node_text(deck, equation) result(text)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: equation
    character(:), allocatable :: text
    integer :: node
    text = ''
    node = equation_node(deck, equation)
    if (node > 0) text = ' at node '//itoa(deck%mesh%node_id(node))//' ('// &
                         trim(merge('u_r', 'u_z', mod(equation, 2) == 1))//')'
  end function node_text

  !> The node (index) of band equation `equation` (0 if none).
  pure integer function equation_node(deck, equation) result(node)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: equation
    integer :: k
    node = 0
    do k = 1, deck%mesh%nnode
      if (deck%mesh%equation(k) == (equation - 1)/2 + 1) then
        node = k
        return
      end if
    end do
  end function equation_node

  !> The deck line of the first element holding the node of band equation
  !> `equation` (its ELEMENT or MESH card; 0 if not known).
  pure integer function equation_line(deck, equation) result(line)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: equation
    integer :: node, e
    line = 0
    node = equation_node(deck, equation)
    if (node == 0 .or. .not. allocated(deck%mesh%element_line)) return
    do e = 1, deck%mesh%nelem
      if (any(deck%mesh%connectivity(:, e) == node)) then
        line = deck%mesh%element_line(e)
        return
      end if
    end do
  end function equation_line

  !> The keyword of the card at deck line `line` ('' if none).
  pure function card_at_line(deck, line) result(keyword)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: line
    character(:), allocatable :: keyword
    integer :: k
    keyword = ''
    if (.not. allocated(deck%cards%cards)) return
    do k = 1, size(deck%cards%cards)
      if (deck%cards%cards(k)%line == line) then
        keyword = deck%cards%cards(k)%keyword
        return
      end if
    end do
  end function card_at_line

  !> The error when a result is not finite (NaN or Inf): located at the
  !> ANALYSIS card, naming what overflowed, so no such value reaches an output.
  subroutine not_finite_error(deck, what, error)
    type(deck_t), intent(in) :: deck
    character(*), intent(in) :: what
    type(error_t), allocatable, intent(inout) :: error
    integer :: k, line
    line = 0
    if (allocated(deck%cards%cards)) then
      do k = 1, size(deck%cards%cards)
        if (deck%cards%cards(k)%keyword == 'ANALYSIS') then
          line = deck%cards%cards(k)%line
          exit
        end if
      end do
    end if
    call set_error(error, what//' is not finite (NaN or Inf): the loads, moduli or prescribed values '// &
      'overflow double precision; check their magnitudes. No results were written.', file=deck%cards%file, &
      line=line, card='ANALYSIS')
  end subroutine not_finite_error
end module visco2d_solve_errors
