!> Kinds and program-wide constants.
module spb_kinds
   use, intrinsic :: iso_fortran_env, only: real64
   implicit none
   private
   public :: wp, version, max_segments, max_profiles, name_len, path_len, max_sweep_values, &
      max_realizations, max_gauges, max_ensemble_columns

   integer, parameter :: wp = real64                  !! working precision
   character(len=*), parameter :: version = '0.6.5'   !! program version: raised with every change of an output
   integer, parameter :: max_segments = 100           !! segments a deck may hold
   integer, parameter :: max_profiles = 100           !! profile_times a deck may hold
   integer, parameter :: max_gauges = 100             !! &gauges positions a deck may hold
   integer, parameter :: max_sweep_values = 1000      !! &sweep values a deck may hold
   integer, parameter :: max_realizations = 1000000   !! &sweep realizations per value
   integer, parameter :: max_ensemble_columns = 16    !! &sweep ensemble_columns a deck may hold
   integer, parameter :: name_len = 32                !! keyword values ('free', ...)
   integer, parameter :: path_len = 512               !! file names and titles
end module spb_kinds
