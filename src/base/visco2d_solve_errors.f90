!> The errors of a failed solve of the base, located in the input file (the
!> model's source_t, of visco2d_model): a
!> singular stiffness (the node, its component and the card of an element
!> holding it), an out-of-balance solution (check_balance), a result that is
!> not finite. Used by the static and quasi-static solutions and, for the
!> same failures, by the contact and dynamic extensions.
module visco2d_solve_errors
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: integer_text
  use visco2d_mesh, only: mesh_t
  use visco2d_model, only: source_t
  implicit none
  private

  public :: check_balance, singular_message, singular_error, node_text, card_at_line, not_finite_error, analysis_error

contains

  !> A solve of a singular stiffness can pass the factor's pivot test (a body
  !> with no support along z: its rigid translation) and return a huge,
  !> meaningless displacement. Then the free equations are out of balance:
  !> the residual K u - R there, round-off for a true solution, is above
  !> 1e-8 of the loads and the support reactions. That is the singular-
  !> stiffness error, at the worst equation.
  subroutine check_balance(mesh, source, residual, fixed, load, error)
    type(mesh_t), intent(in) :: mesh
    type(source_t), intent(in) :: source
    real(dp), intent(in) :: residual(:), load(:)
    logical, intent(in) :: fixed(:)
    type(error_t), allocatable, intent(inout) :: error
    real(dp) :: scale
    integer :: worst
    scale = max(maxval(abs(load)), maxval(abs(merge(residual, 0.0_dp, fixed))), tiny(1.0_dp))
    worst = maxloc(abs(merge(0.0_dp, residual, fixed)), dim=1)
    if (abs(residual(worst)) > 1.0e-8_dp*scale .and. .not. fixed(worst)) call singular_error(mesh, source, worst, error)
  end subroutine check_balance

  !> Message for a factorization failure at band equation `equation`.
  function singular_message(mesh, equation) result(message)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: equation
    character(:), allocatable :: message
    message = 'the stiffness matrix is singular or not positive definite'//node_text(mesh, equation)// &
      ': the body can probably move freely (a rigid-body mode); add FIX cards'// &
      ' that stop it, or check the material constants'
  end function singular_message

  !> The error of a static factorization failure at band equation `equation`,
  !> located at the card that defined an element holding that node.
  subroutine singular_error(mesh, source, equation, error)
    type(mesh_t), intent(in) :: mesh
    type(source_t), intent(in) :: source
    integer, intent(in) :: equation
    type(error_t), allocatable, intent(inout) :: error
    integer :: line
    line = equation_line(mesh, equation)
    call set_error(error, singular_message(mesh, equation), file=source%file, line=line, &
                   card=card_at_line(source, line))
  end subroutine singular_error

  !> ' at node N (u_z)' for band equation `equation` ('' if not found).
  function node_text(mesh, equation) result(text)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: equation
    character(:), allocatable :: text
    integer :: node
    text = ''
    node = equation_node(mesh, equation)
    if (node > 0) text = ' at node '//integer_text(mesh%node_id(node))//' ('// &
                         trim(merge('u_r', 'u_z', mod(equation, 2) == 1))//')'
  end function node_text

  !> The node (index) of band equation `equation` (0 if none).
  pure integer function equation_node(mesh, equation) result(node)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: equation
    integer :: k
    node = 0
    do k = 1, mesh%nnode
      if (mesh%equation(k) == (equation - 1)/2 + 1) then
        node = k
        return
      end if
    end do
  end function equation_node

  !> The input line of the first element holding the node of band equation
  !> `equation` (its ELEMENT or MESH card; 0 if not known).
  pure integer function equation_line(mesh, equation) result(line)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: equation
    integer :: node, e
    line = 0
    node = equation_node(mesh, equation)
    if (node == 0 .or. .not. allocated(mesh%element_line)) return
    do e = 1, mesh%nelem
      if (any(mesh%connectivity(:, e) == node)) then
        line = mesh%element_line(e)
        return
      end if
    end do
  end function equation_line

  !> The keyword of the card at line `line` of the input file ('' if none).
  pure function card_at_line(source, line) result(keyword)
    type(source_t), intent(in) :: source
    integer, intent(in) :: line
    character(:), allocatable :: keyword
    integer :: k
    keyword = ''
    if (.not. allocated(source%lines)) return
    do k = 1, size(source%lines)
      if (source%lines(k) == line) then
        keyword = trim(source%keywords(k))
        return
      end if
    end do
  end function card_at_line

  !> The error when a result is not finite (NaN or Inf): located at the
  !> ANALYSIS card, naming what overflowed, so no such value reaches an output.
  subroutine not_finite_error(source, what, error)
    type(source_t), intent(in) :: source
    character(*), intent(in) :: what
    type(error_t), allocatable, intent(inout) :: error
    call analysis_error(source, error, what//' is not finite (NaN or Inf): the loads, moduli or prescribed values '// &
      'overflow double precision; check their magnitudes. No results were written.')
  end subroutine not_finite_error

  !> An error of the solve located at the deck's ANALYSIS card (its first;
  !> line 0 when the source has none): a Newton solve that did not converge,
  !> a singular tangent, a result not finite.
  subroutine analysis_error(source, error, message)
    type(source_t), intent(in) :: source
    type(error_t), allocatable, intent(inout) :: error
    character(*), intent(in) :: message
    integer :: k, line
    line = 0
    if (allocated(source%lines)) then
      do k = 1, size(source%lines)
        if (source%keywords(k) == 'ANALYSIS') then
          line = source%lines(k)
          exit
        end if
      end do
    end if
    call set_error(error, message, file=source%file, line=line, card='ANALYSIS')
  end subroutine analysis_error
end module visco2d_solve_errors
