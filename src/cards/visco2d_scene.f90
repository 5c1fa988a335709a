!> The scene a deck describes, reduced to the physical effects it calls for.
!> The driver runs only those: no mass without inertia, no Prony history
!> without viscoelastic materials, no contact search without a plate,
!> no body force without gravity, no pad without a PAD card.
module visco2d_scene
  use visco2d_kinds, only: dp
  use visco2d_deck, only: deck_t, analysis_dynamic
  use visco2d_material, only: has_memory
  implicit none
  private

  public :: effects_t, scene_effects, effects_text

  !> The effects a run simulates.
  type :: effects_t
    logical :: inertia = .false.       !< mass and Wilson-theta stepping (ANALYSIS DYNAMIC)
    logical :: viscoelastic = .false.  !< Prony history per Gauss point (a material with memory, beta > 0, in use)
    logical :: contact = .false.       !< contact search (a PLATE card, or a second BODY)
    logical :: gravity = .false.       !< body force rho g (a GRAVITY card)
    logical :: pad = .false.           !< a deformable pad on the plate (a PAD card)
  end type effects_t

contains

  !> The effects a deck calls for: inertia for ANALYSIS DYNAMIC, memory for a
  !> material in use with Prony terms (beta > 0), contact for a PLATE card,
  !> gravity for GRAVITY G > 0.
  function scene_effects(deck) result(effects)
    type(deck_t), intent(in) :: deck
    type(effects_t) :: effects
    integer :: k
    effects = effects_t()
    effects%inertia = deck%analysis == analysis_dynamic
    effects%gravity = deck%loads%gravity > 0.0_dp
    effects%contact = deck%plate%line > 0 .or. deck%body%line > 0
    effects%pad = deck%pad%line > 0
    do k = 1, size(deck%materials)
      if (has_memory(deck%materials(k)) .and. any(deck%mesh%element_material == k)) effects%viscoelastic = .true.
    end do
  end function scene_effects

  !> 'inertia viscoelastic contact pad gravity' (the ones that are on), or 'none'.
  function effects_text(effects) result(text)
    type(effects_t), intent(in) :: effects
    character(:), allocatable :: text
    text = ''
    if (effects%inertia) text = text//' inertia'
    if (effects%viscoelastic) text = text//' viscoelastic'
    if (effects%contact) text = text//' contact'
    if (effects%pad) text = text//' pad'
    if (effects%gravity) text = text//' gravity'
    if (len(text) == 0) then
      text = 'none'
    else
      text = text(2:)
    end if
  end function effects_text
end module visco2d_scene
