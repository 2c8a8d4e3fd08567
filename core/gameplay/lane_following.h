#pragma once
// ALaneFollowingController: an AI controller that drives the AWheeledVehiclePawn it possesses along the
// world's lanes (the world's UZoneGraphSubsystem), through the car's own throttle, steering and brake, so the
// vehicle physics decides where the car goes. The driving itself is sp::zonegraph::Traffic (route choice,
// pure-pursuit steering, the intelligent driver model's speed, junction claims); here every lane-following
// controller of a world is stepped at once each frame, after the actors tick and before physics, so that
// each driver sees every car where the last physics step left it whatever order the actors tick in.

#include <string>
#include <vector>

#include "core/gameplay/controller.h"
#include "core/gameplay/zone_graph.h"
#include "core/zonegraph/traffic.h"

/// An AI controller that drives its possessed AWheeledVehiclePawn along the world's lanes: it keeps to its
/// lane, picks a way at every junction and road end (at random, from RandomSeed), slows for curves, keeps a
/// gap to the car ahead, and waits at a junction while crossing traffic is in it. It drives through the
/// car's throttle, steering and brake, never by moving it. A car more than 6 m from every lane tagged LaneTag
/// (running its way) brakes and waits; possessing it by another controller (a player) takes it over.
SPCLASS()
class ALaneFollowingController : public AController {
    SP_GENERATED_BODY()
  public:
    /// Speed on a free, straight road, m/s (> 0).
    SPPROPERTY(Setter = SetTargetSpeed)
    double TargetSpeed = 10.0;
    /// Bumper-to-bumper gap kept when stopped behind a car, metres (>= 0).
    SPPROPERTY(Setter = SetMinGap)
    double MinGap = 3.0;
    /// Headway kept behind a car at speed, seconds (>= 0).
    SPPROPERTY(Setter = SetTimeGap)
    double TimeGap = 1.2;
    /// The lanes it drives on (a lane tag of the world's AZoneGraphData; "": lanes of every tag).
    SPPROPERTY()
    std::string LaneTag = "Driving";
    /// Seeds its choices of way at junctions (0: from its name), so a run repeats.
    SPPROPERTY()
    int64_t RandomSeed = 0;
    /// False: it brakes and holds the car where it is.
    SPPROPERTY()
    bool bDriving = true;

    /// Sets TargetSpeed (m/s, > 0).
    SPFUNCTION()
    void SetTargetSpeed(double NewSpeed);
    /// Sets MinGap (metres, >= 0).
    SPFUNCTION()
    void SetMinGap(double NewGap);
    /// Sets TimeGap (seconds, >= 0).
    SPFUNCTION()
    void SetTimeGap(double NewGap);

    /// Returns where its car is on its lane as of the last frame (LaneIndex -1 while it is off the lanes or
    /// has not driven yet).
    SPFUNCTION()
    FZoneGraphLaneLocation GetLaneLocation() const;

    /// Returns its car's distance from its lane's centre line in metres, left positive, as of the last frame.
    SPFUNCTION()
    double GetLateralOffset() const { return driver_.lateral; }

    /// Returns the bumper-to-bumper gap in metres to the car (or the stop line) ahead on its way, as of the
    /// last frame; -1 when there is none within its view.
    SPFUNCTION()
    double GetGapAhead() const;

    /// Returns true while it waits (or slows) at a junction: crossing traffic holds it, or there is no room
    /// past it.
    SPFUNCTION()
    bool IsWaitingAtJunction() const { return driver_.waiting; }

    /// Returns the lanes it will drive: the one it is on, then the ones it chose next.
    SPFUNCTION()
    std::vector<int> GetRoute() const { return driver_.route; }

    void BeginPlay() override;
    bool DrivesPawnDirectly() const override { return true; }

    // The driving state the world's traffic steps (sp::zonegraph::Traffic), with the settings of now.
    sp::zonegraph::Driver& driver();
    // Forgets the route (the lanes were rebuilt, or the car changed).
    void resetDriver();

  protected:
    // A new car starts from the lanes it is on, not the last car's route.
    void OnPossess(APawn* pawn) override;

  private:
    sp::zonegraph::Driver driver_;
};
