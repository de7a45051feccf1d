!> The program's identity: what a result and a checkpoint name as the program that made
!> them. The version is raised with every release that changes an output (doc/build.md
!> "Program identity"); the digest of the sources changes with any change of them, so two
!> builds of one identity compute the same numbers (Debug and Release agree to the bit).
module spb_identity
   use spb_kinds, only: version
   use spb_build_id, only: source_digest, git_revision
   implicit none
   private
   public :: program_identity, build_revision

contains

   !> 'spallbar 0.3.0 (source 1a2b3c4d5e6f)': the version and the sources' digest, as the
   !> headers, PREFIX.h5 and the checkpoint write it; a restart needs the same.
   pure function program_identity() result(text)
      character(len=:), allocatable :: text   !! the identity
      text = 'spallbar ' // version // ' (source ' // source_digest() // ')'
   end function program_identity

   !> Where the sources came from: 'git <commit>' (with local changes, when so) or 'no git'.
   pure function build_revision() result(text)
      character(len=:), allocatable :: text   !! the revision, in words
      text = git_revision()
   end function build_revision
end module spb_identity
